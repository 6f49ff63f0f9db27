// The command-line conventions of walkgen's example programs, on top of CLI11.
//
//   CLI::App app{"what the program does (thesis section)", "program_name"};
//   walkgen_examples::cli_defaults(app);        // every option shows its default in --help
//   app.add_option("--out", out_dir, "output folder")->capture_default_str();
//   WALKGEN_CLI_PARSE(app, argc, argv);         // --help: usage, exit 0; a bad option: one line,
//   exit 2
//
// Units belong in the option's description ("[m/s]", "[s]"), ranges in a validator
// (walkgen_examples::positive / non_negative below, CLI::Range, CLI::ExistingDirectory,
// CLI::IsMember).
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "walkgen/core/decimal.hpp"
#include "walkgen/version.hpp"

namespace walkgen_examples {

/// Footer and defaults shared by every example: defaults printed in --help, options may follow
/// positional arguments.
inline void cli_defaults(CLI::App& app) {
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", std::string("walkgen ") + walkgen::kVersion);
  app.get_formatter()->column_width(36);
  app.footer("Part of walkgen's examples (docs/getting-started.md lists them all).");
}

/// CLI11 validator: a number for which ok() holds; `what` ("> 0") names the condition in the
/// error line (the option's description names it in --help). CLI::PositiveNumber of CLI11 2.1
/// prints its range up to 1.8e308 instead.
inline CLI::Validator number_where(const char* what, bool (*ok)(double)) {
  return CLI::Validator(
      [what, ok](std::string& s) -> std::string {
        double v = 0.0;
        if (CLI::detail::lexical_cast(s, v) && ok(v)) return {};
        return std::string("expected a number ") + what + ", got '" + s + "'";
      },
      "");
}

/// `->check(walkgen_examples::positive)`, `->check(walkgen_examples::non_negative)`.
inline const CLI::Validator positive = number_where("> 0", [](double v) { return v > 0.0; });
inline const CLI::Validator non_negative = number_where(">= 0", [](double v) { return v >= 0.0; });

/// CLI11 validator: a decimal integer in [min, the largest T] (CLI11 2.1 alone reads "010" as
/// octal 8 and "0x10" as 16, and clamps a long's overflow); leading zeros are dropped before
/// CLI11 converts it. Attach it with `->transform(...)` (a `->check` may not rewrite the text).
template <typename T>
CLI::Validator decimal_at_least(T min) {
  static_assert(std::is_integral_v<T>, "walkgen: decimal_at_least needs an integer type");
  return CLI::Validator(
      [min](std::string& s) -> std::string {
        const std::string bad = "expected a decimal integer >= " + std::to_string(min) + ", got '";
        if (min < 0 || s.empty() || s.find_first_not_of("0123456789") != std::string::npos) {
          return bad + s + "'";
        }
        constexpr auto max = static_cast<unsigned long long>(std::numeric_limits<T>::max());
        unsigned long long value = 0;
        if (!walkgen::detail::parse_decimal(s, max, &value)) {
          return "expected at most " + std::to_string(max) + ", got '" + s + "'";
        }
        if (value < static_cast<unsigned long long>(min)) return bad + s + "'";
        s = std::to_string(value);  // "007" -> "7": CLI11 then reads it as decimal
        return {};
      },
      "");
}

/// `s` in single quotes for /bin/sh (for the plotting and ffmpeg commands the programs run).
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

#ifdef WALKGEN_SOURCE_DIR  // defined for every program of walkgen_add_example
/// The shell command that runs `script` of walkgen's python/ folder with Debian's Python (numpy,
/// matplotlib) on `argument`, e.g. a plot of the CSV a program wrote.
inline std::string python_command(const std::string& script, const std::string& argument) {
  return "/usr/bin/python3 " + shell_quote(std::string(WALKGEN_SOURCE_DIR) + "/python/" + script) +
         " " + shell_quote(argument);
}
#endif

/// Parses the command line. Returns -1 when the program should go on; otherwise the exit status:
/// 0 after --help (usage on stdout), 2 after a parse error (one line on stderr naming the program,
/// the problem and --help).
inline int cli_parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::printf("%s\n", e.what());
    return 0;
  } catch (const CLI::ParseError& e) {
    // CLI11 checks required arguments before unknown ones; an unknown option is the better news.
    std::string message = e.what();
    const std::vector<std::string> extra = app.remaining();
    if (!extra.empty() && dynamic_cast<const CLI::RequiredError*>(&e) != nullptr) {
      message = "unknown argument(s):";
      for (const auto& a : extra) message += " " + a;
    }
    std::fprintf(stderr, "%s: %s (see %s --help)\n", app.get_name().c_str(), message.c_str(),
                 app.get_name().c_str());
    return 2;
  }
  return -1;
}

}  // namespace walkgen_examples

/// Parses argv into `app` and returns from main() on --help (0) or a bad command line (2).
#define WALKGEN_CLI_PARSE(app, argc, argv)                                      \
  do {                                                                          \
    const int walkgen_cli_rc_ = ::walkgen_examples::cli_parse(app, argc, argv); \
    if (walkgen_cli_rc_ >= 0) return walkgen_cli_rc_;                           \
  } while (false)
