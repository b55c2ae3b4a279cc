// The rule registry: every rule a user can name. Adding a rule family = one file under
// quadrature/rules/, one line in registry.cpp (a named rule or a parametrised family) and
// one line in quadrature/CMakeLists.txt.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "quadrature/rule.h"

namespace radquad {

// Looks a rule up by name: a named rule ("FullGauss") or a parametrised form
// ("Gauss:3x3x2x2"). Throws InputError listing the valid names when none matches.
std::shared_ptr<const Rule> findRule(std::string_view name);

// The named rules, in catalogue order.
std::vector<std::shared_ptr<const Rule>> namedRules();

// The parametrised forms, as users write them (e.g. "Gauss:RsxRtxSuxSv").
std::vector<std::string> parametrisedRuleForms();

}  // namespace radquad
