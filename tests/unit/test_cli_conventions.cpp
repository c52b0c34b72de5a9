// What every command line is expected to answer: --help on every verb (exit 0, its usage on
// standard output) and --version after any verb (the project's one version).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "dem/version.hpp"
#include "support/command.hpp"

namespace dem::test {
namespace {

namespace fs = std::filesystem;

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

// What bash offers after loading `dem completion bash`: COMP_WORDS as bash sets them, the
// completions _dem gives, one per line.
std::string completions(const std::string& dem, const std::string& words, int current) {
  const std::string script = testing::TempDir() + "/dem-completion-test.sh";
  std::ofstream(script, std::ios::binary)
      << ("source <(" + shell_quoted(dem) + " completion bash)\nCOMP_WORDS=(" + words +
          ")\nCOMP_CWORD=" + std::to_string(current) + "\n_dem\nprintf '%s\\n' \"${COMPREPLY[@]}\"\n");
  return run_command("bash " + shell_quoted(script) + " 2>&1").output;
}

TEST_F(CliConventions, BashCompletesVerbsOptionsAndTheirValues) {
  EXPECT_EQ(completions(kDem, "dem ru", 1), "run\n");
  EXPECT_EQ(completions(kDem, "dem run --th", 2), "--threads\n");
  EXPECT_EQ(completions(kDem, "dem chains d --view ''", 4), "x\ny\nz\n");
  EXPECT_EQ(completions(kDem, "dem import a.inp --program b", 4), "ballastdem\n");
  // a client verb's common options, and --json
  const std::string fetch = completions(kDem, "dem fetch 1 --", 3);
  for (const char* option : {"--out", "--server", "--token", "--timeout", "--json", "--help", "--version"})
    EXPECT_NE(fetch.find(std::string(option) + "\n"), std::string::npos) << option << " in " << fetch;
  // every verb of dem's overview is offered
  const std::string verbs = completions(kDem, "dem ''", 1);
  for (const char* verb : kVerbs) EXPECT_NE(verbs.find(std::string(verb) + "\n"), std::string::npos) << verb;
  const CommandResult other = run_dem("completion zsh 2>&1");
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_NE(other.output.find("only bash"), std::string::npos) << other.output;
}

// Every option a verb's --help lists is one its parser takes, and the other way round: both come
// from the verb's one description, so an option cannot be added to one and not the other.
TEST_F(CliConventions, EveryVerbsHelpListsTheOptionsItsCompletionOffers) {
  for (const char* verb : kVerbs) {
    const std::string help = run_dem(std::string(verb) + " --help").output;
    std::string offered = completions(kDem, std::string("dem ") + verb + " --", 2);
    for (std::size_t at = 0, end; (end = offered.find('\n', at)) != std::string::npos; at = end + 1) {
      const std::string option = offered.substr(at, end - at);
      EXPECT_NE(help.find(option == "--help" ? "-h, --help" : "  " + option), std::string::npos)
          << verb << ": " << option << " is offered but not in its help:\n"
          << help;
    }
  }
}

// An independent tester's findings on the parsing: a flag took a value and ignored it
// (--wait=false waited, --json=false printed JSON), a flag given twice passed, an empty value went
// on to fail later with exit 1 ("filesystem error: cannot create directories"), --timeout took
// hexadecimal, and --json with --quiet printed no end.
TEST_F(CliConventions, FlagsTakeNoValueAndNothingIsGivenTwiceOrEmpty) {
  const std::pair<const char*, const char*> cases[] = {
      {"run s.json --out o --quiet=false", "--quiet takes no value"},
      {"status 1 --json=0", "--json takes no value"},
      {"run s.json --out o --quiet --quiet", "--quiet is given 2 times"},
      {"submit s.json --wait --wait", "--wait is given 2 times"},
      {"run s.json --out ''", "--out is given an empty value"},
      {"fetch 1 --out=", "--out is given an empty value"},
      // "=" and nothing took the next argument as the value: the study ran into a folder "--plan"
      {"study s.json --out= --plan", "--out is given an empty value"},
      {"run s.json --out= --quiet", "--out is given an empty value"},
      {"chains r --times '' --out f.svg", "--times is given an empty value"},
      {"status 1 --timeout 0x10", "--timeout is a number of seconds"},
      {"submit s.json --quiet --json", "--quiet and --json"},
  };
  for (const auto& [args, said] : cases) {
    const CommandResult r = run_dem(std::string(args) + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(said), std::string::npos) << args << ": " << r.output;
  }
}

// `dem study` refused --json without --submit but ran a study here with --server given (a forgotten
// --submit), and followed a study with --id ignoring --jobs or --plan.
TEST_F(CliConventions, StudyRefusesTheOtherModesOptions) {
  const std::pair<const char*, const char*> cases[] = {
      {"study s.json --out o --server http://127.0.0.1:1", "--server goes with --submit or --id"},
      {"study s.json --out o --token t", "--token goes with --submit or --id"},
      {"study --id 3 --out o --jobs 2", "--jobs does not go with --id"},
      {"study --id 3 --out o --plan", "--plan does not go with --id"},
  };
  for (const auto& [args, said] : cases) {
    const CommandResult r = run_dem(std::string(args) + " 2>&1");
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(said), std::string::npos) << args << ": " << r.output;
  }
}

// `dem help run` printed dem's overview, and `dem help bogus` exited 0.
TEST_F(CliConventions, HelpOfAVerbIsItsOwn) {
  const CommandResult run = run_dem("help run");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.output, run_dem("run --help").output);
  EXPECT_EQ(run_dem("help bogus 2>&1").exit_code, 2);
  // every verb's help ends with its exit status (plot, chains and deposits had none)
  for (const char* verb : kVerbs)
    EXPECT_NE(run_dem(std::string(verb) + " --help").output.find("exit status"), std::string::npos) << verb;
}

// Bash completion kept names with spaces whole only after `mapfile` (it offered "a" and "b.json"
// for "a b.json"), and read --view=VALUE, which bash splits at '=' (it offered files there).
TEST_F(CliConventions, CompletionKeepsNamesWithSpacesAndReadsEqualsValues) {
  const fs::path dir = fs::path(testing::TempDir()) / "dem-completion-spaces";
  fs::remove_all(dir);
  fs::create_directories(dir / "dir one");
  std::ofstream(dir / "a b.json") << "{}";
  const std::string in_dir = "cd " + shell_quoted(dir) + " && ";
  const std::string script = testing::TempDir() + "/dem-completion-spaces.sh";
  auto complete = [&](const std::string& words, int current) {
    std::ofstream(script, std::ios::binary)
        << ("source <(" + shell_quoted(kDem) + " completion bash)\nCOMP_WORDS=(" + words +
            ")\nCOMP_CWORD=" + std::to_string(current) + "\n_dem\nprintf '%s\\n' \"${COMPREPLY[@]}\"\n");
    return run_command(in_dir + "bash " + shell_quoted(script) + " 2>&1").output;
  };
  EXPECT_EQ(complete("dem run a", 2), "a b.json\n");
  EXPECT_EQ(complete("dem run x.json --out di", 4), "dir one\n");
  EXPECT_EQ(complete("dem chains d --view = ''", 5), "x\ny\nz\n");
  EXPECT_EQ(complete("dem chains d --view =", 4), "x\ny\nz\n");
  fs::remove_all(dir);
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
