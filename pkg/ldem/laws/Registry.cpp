#include "ldem/laws/Registry.hpp"

#include <string>
#include <vector>

namespace ldem {

std::vector<std::string> barLawNames() { return {kBarLawNames.begin(), kBarLawNames.end()}; }

}  // namespace ldem
