#include "ldem/CurveCsv.hpp"

#include <stdexcept>

namespace ldem {

const char* CurveCsvWriter::header() {
    return "step,time_s,mean_strain,stress_MPa,stress_top_MPa,external_work_J,kinetic_J,elastic_J,fracture_J,"
           "damping_J,damaged_bars,broken_bars";
}

CurveCsvWriter::CurveCsvWriter(const std::string& path) : out_(path) {
    if (!out_) throw std::runtime_error("cannot write " + path);
    out_.precision(10);
    out_ << header() << '\n' << std::flush;
}

void CurveCsvWriter::write(const CurvePoint& p) {
    out_ << p.step << ',' << p.time << ',' << p.meanStrain << ',' << p.stressBottom * 1e-6 << ','
         << p.stressTop * 1e-6 << ',' << p.externalWork << ',' << p.kinetic << ',' << p.elastic << ','
         << p.fracture << ',' << p.damping << ',' << p.damaged << ',' << p.broken << '\n'
         << std::flush;
}

}  // namespace ldem
