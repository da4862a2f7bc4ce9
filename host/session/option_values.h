#pragma once
// One option's value, parsed and range-checked by its row's kind (session/option_table.h), and
// the words the help and the error messages use for the range: both come from the row's bounds,
// so a range is written once.
#include <string>

#include "session/option_table.h"

namespace mixtrace {

// Throws mixtrace::Error, one line naming the option and what it expects, e.g.
// "invalid value '0' for --width: expected an integer in 1..16384".
OptionValue parseOptionValue(const OptionRow& row, const std::string& value);

// The accepted range as --help writes it: "1..16384", "N >= 1", "> 0", "0 < A < 1"; "" for kinds
// without one.
std::string rangeText(const OptionRow& row);

// What a valid value is, as the error messages say it: "an integer in 1..16384".
std::string expectedValue(const OptionRow& row);

}  // namespace mixtrace
