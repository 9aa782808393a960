// pelage: the command line. Parses arguments and calls library functions; every error becomes a
// "pelage: error:" message and a non-zero exit status, never a crash: 2 for bad input (a usage
// error, a bad file or value), 3 for an internal error, 4 when memory runs out.
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "pelage/util/error.h"

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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pelage: animated furred creatures (Van Gelder & Wilhelms 1997 fur model)"};
  app.require_subcommand(1);
  pelage::app::CommonOptions common;
  common.add(app, false);
  app.set_version_flag("--version", "pelage 0.1.0");
  pelage::app::addInfoCommand(app);
  pelage::app::addSkinCommand(app);
  pelage::app::addHairCommand(app);
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
    for (const CLI::App* c : app.get_subcommands()) command = c->get_name();
    return usageError(e.what(), command);
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
    std::fprintf(stderr, "pelage: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
