#pragma once
/// @file worst_cases.h
/// @brief How many worst cases a report lists: the one option both reports
/// take (ReportOptions::worst, LevelSetCheckOptions::worst), declared once.
#include <cstddef>
#include <cstdint>
#include <string>

#include "svo/core/option_info.h"

namespace svo::validate {

/// @brief The rule of `worst`: a whole number from 0 to 1000000.
/// @param worst the number given, signed so that a negative one meets this rule
/// @param name  the caller's flag or keyword ("--worst", "worst")
/// @throw svo::InvalidInput "<name> <value>: ..." (argument() @a name)
void checkWorst(int64_t worst, const std::string& name);

/// @brief Shows a report's `worst` field to an option visitor
/// (svo/core/option_info.h): the declaration both reports' forEachOption use.
template <typename Visit>
void visitWorst(size_t& worst, Visit&& visit)
{
    // Read signed, so that -1 gets the rule's message rather than a parser's.
    visit(OptionInfo{"validate::worst", "worst", "Worst cases listed of each kind, 0 to 1000000"},
          CheckedInteger<size_t, int64_t>{worst, checkWorst});
}

} // namespace svo::validate
