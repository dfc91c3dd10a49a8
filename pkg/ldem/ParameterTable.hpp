// The parameter table: every parameter of a cube test, whole (CubeTestParams)
// and by name, generated from the lists of Parameters.hpp, for the Python
// bindings, ldem.CubeTest and its command line. The cube itself is built by
// cubeTestSpecimen (Specimen.hpp).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "ldem/Loading.hpp"
#include "ldem/Material.hpp"
#include "ldem/Parameters.hpp"
#include "ldem/RunParams.hpp"

namespace ldem {

struct CubeGeometry {
    LDEM_GEOMETRY_PARAMETERS(LDEM_DECLARE_MEMBER)
    // Modules along one side; throws unless size is a positive multiple of L0.
    int modules() const;
    void validate() const;
};

struct CubeTestParams {
    CubeGeometry geometry;
    Material material;
    LoadingParams loading;
    RunParams run;
    void validate() const;
};

// A parameter's value: a number, a count, or the name of a choice.
using ParamValue = std::variant<double, std::int64_t, std::string>;

struct ParamInfo {
    std::string group;  // geometry, material, loading or run
    std::string name, unit, help;
    std::string kind;   // "float", "int", "choice" or "names" (some of the choices, comma-separated)
    Domain domain;
    ParamValue defaultValue;
};

// Every parameter, in declaration order: geometry, material, loading, run.
const std::vector<ParamInfo>& cubeTestParameters();

// The cube's own defaults over the table's (which are every specimen's): its
// drive paced near the peak and while a crack runs (dynamics/CrackPace.hpp): a
// constant rate feeds the crack that runs through a large cube at its peak, and
// a beam at its own period's rate needs no pace (results/dynamics/README.md).
const std::vector<std::pair<std::string, ParamValue>>& cubeOwnDefaults();
// A cube test at its defaults: the table's, then cubeOwnDefaults().
CubeTestParams cubeTestDefaults();
// A specimen's own defaults over the table's, for one described in a file
// (py/ldem/specimen.py): rule (c) sets its rate from its own fundamental
// period, eps_p in kRatePeriods periods (dynamics/QuasiStatic.hpp), where the
// table's strain_rate, a cube's, is a guess. A file that gives strain_rate is driven at it.
const std::vector<std::pair<std::string, ParamValue>>& specimenOwnDefaults();

// By name; an unknown name, a wrong type or an unknown choice throws
// std::invalid_argument naming the parameter.
ParamValue getParameter(const CubeTestParams& p, const std::string& name);
void setParameter(CubeTestParams& p, const std::string& name, const ParamValue& v);
// The same on one group's struct (its own names only).
ParamValue getParameter(const Material& m, const std::string& name);
void setParameter(Material& m, const std::string& name, const ParamValue& v);
ParamValue getParameter(const LoadingParams& l, const std::string& name);
void setParameter(LoadingParams& l, const std::string& name, const ParamValue& v);
ParamValue getParameter(const RunParams& r, const std::string& name);
void setParameter(RunParams& r, const std::string& name, const ParamValue& v);

}  // namespace ldem
