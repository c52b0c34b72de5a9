// `cmake --install` into a prefix: the programs, the viewer, the cases, the docs and the bash
// completion land there, and the installed dem-server serves the viewer and the cases it finds
// beside itself, not the source tree's (no path of the source tree is compiled in).
#include <string>

#include <nlohmann/json.hpp>

#include "support/command.hpp"
#include "support/server_test.hpp"

namespace dem::test {
namespace {

class Install : public ServerTest {};

TEST_F(Install, TheInstalledServerFindsTheViewerAndTheCasesBesideItself) {
  const fs::path prefix = dir_ / "prefix";
  const CommandResult installed =
      run_command("cmake --install " + shell_quoted(DEM_BINARY_DIR) + " --prefix " + shell_quoted(prefix) + " 2>&1");
  ASSERT_EQ(installed.exit_code, 0) << installed.output;
  for (const char* file : {"bin/dem", "bin/dem-server", "share/dem/web/index.html", "share/dem/cases/demo/spec.json",
                           "share/doc/dem/docs/api.md", "share/doc/dem/LICENSE",
                           "share/bash-completion/completions/dem", "share/dem/clients/python/demclient/__init__.py"})
    EXPECT_TRUE(fs::is_regular_file(prefix / file)) << file;

  // what only the installed copies hold: served only if the server reads them there
  const std::string marker = "<!-- installed copy -->";
  write_text(prefix / "share/dem/web/index.html", read_bytes(prefix / "share/dem/web/index.html") + marker);
  fs::create_directories(prefix / "share/dem/cases/installed-only");
  fs::copy_file(prefix / "share/dem/cases/demo/spec.json", prefix / "share/dem/cases/installed-only/spec.json");
  write_text(prefix / "share/dem/cases/installed-only/README.md", "# installed only\n");

  ServerProcess server(dir_ / "data", {}, {}, prefix / "bin/dem-server");
  client::HttpClient http(server.url());
  const client::Response page = http.get("/");
  EXPECT_EQ(page.status, 200);
  EXPECT_NE(page.body.find(marker), std::string::npos) << "the viewer was not served from the prefix";
  const client::Response cases = http.get("/api/v1/cases");
  ASSERT_EQ(cases.status, 200) << cases.body;
  EXPECT_NE(cases.body.find("installed-only"), std::string::npos) << cases.body;

  // the installed dem and its completion
  const CommandResult version = run_command(shell_quoted(prefix / "bin/dem") + " --version");
  EXPECT_EQ(version.output.rfind("dem ", 0), 0u) << version.output;
  EXPECT_NE(read_bytes(prefix / "share/bash-completion/completions/dem").find("complete -o filenames"),
            std::string::npos);
}

// A --web or --cases that is not a folder is refused at start (a file given as --web was served
// at / as application/octet-stream), and a viewer not found where it was looked for is said,
// naming the place (nothing was said).
TEST_F(Install, AViewerFolderThatIsNotOneIsRefusedOrSaid) {
  const fs::path file = dir_ / "a-file";
  write_text(file, "not a folder");
  for (const std::string option : {"--web", "--cases"}) {
    const CommandResult r =
        run_command(shell_quoted(DEM_BINARY_DIR "/dem-server") + " --data " + shell_quoted(dir_ / "data") +
                    " --port 0 " + option + " " + shell_quoted(file) + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << option << ": " << r.output;
    EXPECT_NE(r.output.find(option + ": " + file.string() + " is not a folder"), std::string::npos) << r.output;
  }
  const CommandResult empty = run_command(shell_quoted(DEM_BINARY_DIR "/dem-server") + " --data '' --port 0 2>&1");
  EXPECT_EQ(empty.exit_code, 2) << empty.output;
  EXPECT_NE(empty.output.find("--data"), std::string::npos) << empty.output;

  // a copy of dem-server with nothing beside it: it starts, and says where it looked
  fs::create_directories(dir_ / "lonely" / "bin");
  fs::copy_file(DEM_BINARY_DIR "/dem-server", dir_ / "lonely" / "bin" / "dem-server");
  const fs::path said = dir_ / "stderr.txt";
  {
    ServerProcess server(dir_ / "data", {}, said, dir_ / "lonely" / "bin" / "dem-server");
    client::HttpClient http(server.url());
    EXPECT_EQ(http.get("/api/v1/health").status, 200);
  }
  const std::string log = read_bytes(said);
  EXPECT_NE(log.find("the viewer (built by scripts/build) is not at " + (dir_ / "lonely" / "share/dem/web").string()),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("the bundled cases are not at"), std::string::npos) << log;
}

}  // namespace
}  // namespace dem::test
