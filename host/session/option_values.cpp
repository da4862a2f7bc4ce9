#include "session/option_values.h"

#include <cctype>
#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "util/error.h"

namespace mixtrace {
namespace {

// An integer row whose upper bound is the largest int has no upper bound worth stating.
bool unbounded(const OptionRow& row) { return row.maxInteger == INT_MAX; }

// "0", "1", "180", "0.5": as short as the number allows.
std::string numberText(double x) {
  char b[32];
  std::snprintf(b, sizeof(b), "%g", x);
  return b;
}

std::string joined(const std::vector<std::string>& items, const char* separator) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

[[noreturn]] void refuse(const OptionRow& row, const std::string& value) {
  throw Error("invalid value '" + value + "' for " + row.name + ": expected " + expectedValue(row));
}

// The whole string must be the number: no leading space (strtod/strtoll would skip it), no
// trailing text.
bool strictInteger(const std::string& text, long long& number) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  errno = 0;
  char* end = nullptr;
  number = std::strtoll(text.c_str(), &end, 10);
  return errno != ERANGE && end == text.c_str() + text.size();
}

// strtod accepts "inf" and "nan"; neither is a usable value of any option.
bool strictFiniteNumber(const std::string& text, double& number) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
  errno = 0;
  char* end = nullptr;
  number = std::strtod(text.c_str(), &end);
  return errno != ERANGE && end == text.c_str() + text.size() && std::isfinite(number);
}

bool inRange(const OptionRow& row, double x) {
  return row.openRange ? x > row.minNumber && x < row.maxNumber : x >= row.minNumber && x <= row.maxNumber;
}

// "X,Y,Z": three numbers separated by commas, nothing else. Each within float's range: camera
// values end up in float, where 1e300 would become infinity.
bool parseVector(const std::string& value, std::array<double, 3>& v) {
  size_t start = 0;
  for (size_t i = 0; i < 3; ++i) {
    const size_t comma = i < 2 ? value.find(',', start) : value.size();
    if (comma == std::string::npos || (i == 2 && value.find(',', start) != std::string::npos)) return false;
    if (!strictFiniteNumber(value.substr(start, comma - start), v[i]) || std::abs(v[i]) > FLT_MAX) return false;
    start = comma + 1;
  }
  return true;
}

}  // namespace

std::string rangeText(const OptionRow& row) {
  switch (row.kind) {
    case ValueKind::Integer: {
      const std::string word = row.zeroWord ? std::string("|") + row.zeroWord : "";
      if (unbounded(row)) return std::string(row.placeholder) + " >= " + std::to_string(row.minInteger) + word;
      return std::to_string(row.minInteger) + ".." + std::to_string(row.maxInteger) + word;
    }
    case ValueKind::Number:
      if (std::isinf(row.maxNumber)) return "> " + numberText(row.minNumber);
      if (row.openRange)
        return numberText(row.minNumber) + " < " + row.placeholder + " < " + numberText(row.maxNumber);
      return numberText(row.minNumber) + ".." + numberText(row.maxNumber);
    case ValueKind::Choice: return joined(row.choices, "|");
    default: return "";
  }
}

std::string expectedValue(const OptionRow& row) {
  const std::string unit = row.unit ? std::string(" of ") + row.unit : "";
  switch (row.kind) {
    case ValueKind::Integer: {
      const std::string word = row.zeroWord ? std::string(" or ") + row.zeroWord : "";
      if (unbounded(row)) return "an integer >= " + std::to_string(row.minInteger) + word;
      return "an integer in " + std::to_string(row.minInteger) + ".." + std::to_string(row.maxInteger) + word;
    }
    case ValueKind::Number:
      if (std::isinf(row.maxNumber)) return "a number" + unit + " > " + numberText(row.minNumber);
      if (row.openRange)
        return "a number" + unit + " between " + numberText(row.minNumber) + " and " + numberText(row.maxNumber) +
               " (exclusive)";
      return "a number" + unit + " in " + numberText(row.minNumber) + ".." + numberText(row.maxNumber);
    case ValueKind::Choice: return "one of " + joined(row.choices, ", ");
    case ValueKind::Vector3: return "three finite numbers X,Y,Z";
    case ValueKind::Text: return "a non-empty value";
    case ValueKind::Flag: return "no value";
  }
  return "";
}

OptionValue parseOptionValue(const OptionRow& row, const std::string& value) {
  OptionValue parsed;
  parsed.text = value;
  switch (row.kind) {
    case ValueKind::Flag:
    case ValueKind::Text: break;
    case ValueKind::Integer:
      if (row.zeroWord && value == row.zeroWord) {
        parsed.integer = 0;
        break;
      }
      if (!strictInteger(value, parsed.integer) || parsed.integer < row.minInteger || parsed.integer > row.maxInteger)
        refuse(row, value);
      break;
    case ValueKind::Number:
      if (!strictFiniteNumber(value, parsed.number) || !inRange(row, parsed.number)) refuse(row, value);
      break;
    case ValueKind::Choice: {
      bool known = false;
      for (const std::string& choice : row.choices) known = known || choice == value;
      if (!known)
        throw Error("unknown " + std::string(row.choiceNoun) + " '" + value + "' for " + row.name +
                    " (valid: " + joined(row.choices, ", ") + ")");
      break;
    }
    case ValueKind::Vector3:
      if (!parseVector(value, parsed.vector)) refuse(row, value);
      break;
  }
  return parsed;
}

}  // namespace mixtrace
