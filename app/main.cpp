// pelage: the command line. Parses arguments and calls library functions; every error becomes a
// "pelage: error:" message and a non-zero exit status, never a crash: 2 for bad input (a usage
// error, a bad file or value), 3 for an internal error, 4 when memory runs out.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "pelage/util/error.h"
#include "pelage/util/interrupt.h"
#include "pelage/util/version.h"

namespace {

// The subcommands' names, for the message about an unknown one.
std::string commandNames(const CLI::App& app) {
  std::string names;
  for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + c->get_name();
  return names;
}

int usageError(const std::string& message, const std::string& command) {
  std::fprintf(stderr, "pelage: error: %s\n", message.c_str());
  std::fprintf(stderr, "Run 'pelage%s --help' for the options.\n",
               command.empty() ? "" : (" " + command).c_str());
  return 2;
}

// Levenshtein distance (small strings: option names).
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// "unknown option --frame (did you mean --frames?)" for the first argument that looks like an
// option `command` does not have; "" when there is none.
std::string unknownOption(const CLI::App& command, const std::vector<std::string>& args) {
  std::vector<std::string> names;
  for (const CLI::Option* o : command.get_options())
    for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
  for (const std::string& a : args) {
    if (a.rfind("--", 0) != 0 || a.size() < 3) continue;
    const std::string name = a.substr(0, a.find('='));
    if (std::find(names.begin(), names.end(), name) != names.end()) continue;
    std::string best;
    std::size_t bestDistance = 4;  // suggestions within 3 edits, or a prefix of a name
    for (const std::string& n : names) {
      const std::size_t d = n.rfind(name, 0) == 0 ? 1 : editDistance(name, n);
      if (d < bestDistance) {
        bestDistance = d;
        best = n;
      }
    }
    return "unknown option " + pelage::excerpt(name) +
           (best.empty() ? "" : " (did you mean " + best + "?)");
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  // Ctrl-C and SIGTERM stop the command at its next frame: what it was writing is removed, it says
  // "interrupted" and exits with 128 + the signal (130, 143), as a shell reports a killed program.
  pelage::catchInterrupts();
  CLI::App app{"pelage: animated furred creatures (Van Gelder & Wilhelms 1997 fur model)"};
  app.require_subcommand(1);
  pelage::app::CommonOptions common;
  common.add(app, false);
  app.set_version_flag("--version", std::string("pelage ") + pelage::util::kVersion);
  pelage::app::addInfoCommand(app);
  pelage::app::addSkinCommand(app);
  pelage::app::addHairCommand(app);
  pelage::app::addGroomCommand(app);
  pelage::app::addBenchCommand(app);
  pelage::app::addAnalyzeCommand(app);
  pelage::app::addExportCommand(app);
#ifdef PELAGE_HAVE_VIEWER
  pelage::app::addViewCommand(app);
  pelage::app::addRenderCommand(app);
#endif
  app.parse_complete_callback([&] { common.apply(); });
  std::vector<std::string> args(argv + 1, argv + argc);
  // An unknown command names itself and lists the commands (CLI11 would say "not expected").
  for (const std::string& a : args) {
    if (a.rfind("-", 0) == 0) break;
    bool known = false;
    for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; }))
      known = known || c->get_name() == a;
    if (!known)
      return usageError("unknown command '" + a + "' (commands: " + commandNames(app) + ")", "");
    break;
  }
  args = pelage::app::normalizeArguments(args);
  std::string command;
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them reversed
    app.parse(reversed);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own status (the viewer's)
  } catch (const CLI::ParseError& e) {
    const CLI::App* selected = &app;
    for (const CLI::App* c : app.get_subcommands()) {
      command = c->get_name();
      selected = c;
    }
    if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
      const std::string unknown = unknownOption(*selected, args);
      if (!unknown.empty()) return usageError(unknown, command);
    }
    return usageError(e.what(), command);
  } catch (const pelage::Interrupted& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "%spelage: interrupted\n", ::isatty(2) == 1 ? "\n" : "");
    return 128 + e.signal();
  } catch (const pelage::InputError& e) {
    std::fprintf(stderr, "pelage: error: %s\n", pelage::app::describe(e).c_str());
    return 2;
  } catch (const pelage::InternalError& e) {
    std::fprintf(stderr, "pelage: %s\n", e.what());
    return 3;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "pelage: error: out of memory\n");
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "pelage: error: %s\n", pelage::shortenLongWords(e.what()).c_str());
    return 1;
  }
  return 0;
}
