// What every command line is expected to answer: --help on every verb (exit 0, its usage on
// standard output) and --version after any verb (the project's one version).
#include <gtest/gtest.h>

#include "dem/version.hpp"
#include "support/command.hpp"

namespace dem::test {
namespace {

class CliConventions : public DemCommandTest {};

const char* const kVerbs[] = {"run",    "validate", "import", "study",  "plot",   "chains", "deposits",
                              "submit", "status",   "list",   "cancel", "resume", "watch",  "fetch"};

TEST_F(CliConventions, EveryVerbAnswersHelpWithItsUsage) {
  for (const char* verb : kVerbs) {
    for (const char* help : {"--help", "-h"}) {
      const CommandResult r = run_command(shell_quoted(kDem) + " " + verb + " " + help + " 2>/dev/null");
      EXPECT_EQ(r.exit_code, 0) << verb << " " << help << ": " << r.output;
      EXPECT_EQ(r.output.rfind(std::string("usage: dem ") + verb, 0), 0u) << verb << " " << help << ": " << r.output;
    }
  }
  const CommandResult top = run_dem("--help");
  EXPECT_EQ(top.exit_code, 0);
  for (const char* verb : kVerbs) EXPECT_NE(top.output.find(std::string("dem ") + verb), std::string::npos) << verb;
}

TEST_F(CliConventions, VersionIsAnsweredAloneAndAfterAnyVerb) {
  const std::string expected = std::string("dem ") + kVersion + "\n";
  EXPECT_EQ(run_dem("--version").output, expected);
  EXPECT_EQ(run_dem("version").output, expected);
  // not after a verb there is not (an independent tester's finding: it printed the version, exit 0)
  const CommandResult unknown = run_dem("nosuchverb --version 2>&1");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("unknown command \"nosuchverb\""), std::string::npos) << unknown.output;
  for (const char* verb : kVerbs) {
    const CommandResult r = run_command(shell_quoted(kDem) + " " + verb + " --version 2>&1");
    EXPECT_EQ(r.exit_code, 0) << verb;
    EXPECT_EQ(r.output, expected) << verb;
  }
}

// The version is set once (CMakeLists.txt's project()); the README and the changelog name it.
TEST_F(CliConventions, TheReadmeAndTheChangelogNameTheVersion) {
  const std::string version = kVersion;
  EXPECT_NE(read(DEM_SOURCE_DIR "/README.md").find("Version " + version + " ("), std::string::npos);
  const std::string changelog = read(DEM_SOURCE_DIR "/CHANGELOG.md");
  EXPECT_EQ(changelog.find("\n## "), changelog.find("\n## " + version)) << "the newest entry is not " << version;
  EXPECT_EQ(read(DEM_SOURCE_DIR "/web/package.json").find("\"version\""), std::string::npos)
      << "the viewer's package.json has a version of its own";
}

}  // namespace
}  // namespace dem::test
