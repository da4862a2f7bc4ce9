#pragma once
// Every option of the command line, declared once (as Mitsuba declares a plugin's parameters):
// its name, the placeholder of its value, what values it takes, its default, its help text, its
// group in --help and the commands that take it. The parser (options.cpp), --help (help_text.cpp)
// and the defaults of RenderOptions and CompareOptions all read these rows; a new option is one
// row in option_table.cpp plus the field it sets.
#include <array>
#include <string>
#include <vector>

namespace mixtrace {

struct RenderOptions;
struct CompareOptions;

// The commands that take an option, as bits: view takes most of render's options.
enum OptionCommands : unsigned {
  kForRender = 1u << 0,
  kForView = 1u << 1,
  kForCompare = 1u << 2,
  kForRenderAndView = kForRender | kForView,
};

// The sections of --help, in their order there.
enum class OptionGroup { Input, Output, Camera, Sampling, Execution, View, Compare };

enum class ValueKind {
  Flag,      // takes no value: given means on
  Text,      // any non-empty string: a path, a device's name
  Integer,   // a decimal integer in [minInteger, maxInteger]
  Number,    // a finite decimal number in [minNumber, maxNumber], or the open interval when openRange
  Choice,    // one of choices()
  Vector3,   // three finite numbers X,Y,Z within float's range
};

// A value as parsed (and range-checked) by its row's kind.
struct OptionValue {
  std::string text;                  // as given; what Text and Choice store
  long long integer = 0;             // Integer
  double number = 0.0;               // Number
  std::array<double, 3> vector{};    // Vector3
};

// Where a command line's values go. Only the destination of the command being parsed is set.
struct OptionDestination {
  RenderOptions* render = nullptr;     // render and view
  CompareOptions* compare = nullptr;   // compare
  std::string* viewScript = nullptr;   // view --script
};

struct OptionRow {
  const char* name;             // "--width"
  const char* shortName;        // "-q", or nullptr
  const char* placeholder;      // the value in --help ("W", "FILE", "on|off"); nullptr for a flag
  ValueKind kind;
  unsigned commands;            // OptionCommands bits
  OptionGroup group;
  long long minInteger = 0, maxInteger = 0;   // Integer: the accepted range
  double minNumber = 0.0, maxNumber = 0.0;    // Number: the accepted range (maxNumber may be inf)
  bool openRange = false;                     // Number: both ends excluded
  // Integer: a word taken in place of the value 0, which the row's store reads as "choose for me"
  // (--cells auto); nullptr when the option has none. 0 itself stays refused unless in range.
  const char* zeroWord = nullptr;
  const char* unit = nullptr;                 // Number: what it counts ("seconds"), for messages
  const char* choiceNoun = nullptr;           // Choice: what a value is ("method"), for messages
  std::vector<std::string> choices;           // Choice: the values, in the order help lists them
  // The value the option has when it is not given, written as on the command line and applied
  // through the same parser (so it passes its own range check); "" when not given means unset.
  std::string defaultValue;
  // How --help states the default where it is not just defaultValue ("16 when neither --spp nor
  // --time is given"); "" to show defaultValue.
  std::string defaultNote;
  // The description in --help, wrapped by the help generator. "{range}" becomes the accepted range
  // ("1..16384", "N >= 1", "0 < A < 1") and "{default}" the default; without "{default}", a row
  // with a default gets " (default: ...)" at the end. A '\n' forces a line break.
  std::string help;
  // Lines --help prints after the description (the method list), already laid out; "" for none.
  std::string (*details)() = nullptr;
  void (*store)(OptionDestination& to, const OptionValue& value) = nullptr;

  bool takesValue() const { return kind != ValueKind::Flag; }
  bool takenBy(unsigned command) const { return (commands & command) != 0; }
  // The default as --help states it ("" where the option has none).
  std::string shownDefault() const { return defaultNote.empty() ? defaultValue : defaultNote; }
};

// The rows, in --help order within each group.
const std::vector<OptionRow>& optionTable();

// The row called `name` (long or short) that `command` (an OptionCommands bit) takes; nullptr when
// none. findOptionRowOfAnyCommand: a row of that name for any command, to tell an unknown option
// from another command's.
const OptionRow* findOptionRow(const std::string& name, unsigned command);
const OptionRow* findOptionRowOfAnyCommand(const std::string& name);

// The commands a row is for, as words: "render and view", "compare".
std::string commandsOf(const OptionRow& row);

}  // namespace mixtrace
