// curve.csv: one row per record, flushed as it is written so that a run that
// fails or is interrupted keeps every row up to that point.
#pragma once
#include <fstream>
#include <string>

#include "ldem/Simulation.hpp"

namespace ldem {

class CurveCsvWriter {
public:
    explicit CurveCsvWriter(const std::string& path);
    void write(const CurvePoint& p);
    static const char* header();

private:
    std::ofstream out_;
};

}  // namespace ldem
