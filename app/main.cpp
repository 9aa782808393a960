// pelage: the command line. Parses arguments and calls library functions; every error becomes a
// message and a non-zero exit status, never a crash.
#include <cstdio>
#include <exception>
#include <new>

#include "commands.h"
#include "options.h"
#include "pelage/util/error.h"
#include "pelage/util/parallel.h"

int main(int argc, char** argv) {
  CLI::App app{"pelage: animated furred creatures (Van Gelder & Wilhelms 1997 fur model)"};
  app.require_subcommand(1);
  int threads = 0;
  app.add_option("--threads", threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024));
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
  app.parse_complete_callback([&] { pelage::setThreadCount(threads); });
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
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
