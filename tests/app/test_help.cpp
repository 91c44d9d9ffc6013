// Every command answers --help (and `haif help COMMAND`) with its own options, exit 0, and does
// nothing else; an unknown command's help is an error.
#include "haif_process.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace haif::test {
namespace {

TEST(Help, EveryCommandPrintsItsOwnOptionsAndDoesNothingElse) {
  const auto dir = scratchDir("haif_help");
  const std::pair<const char*, const char*> commands[] = {
      {"run", "--budget-ms"}, {"bench", "--engines"},   {"calibrate", "--out"}, {"compare", "--left"},
      {"reel", "--check"},    {"diff", "--threshold"}, {"stress", "--quick"},  {"suite", "--shard"},
      {"assets", "--out"}};
  for (const auto& [name, option] : commands) {
    for (const std::string& form : {std::string(name) + " --help", std::string(name) + " -h", "help " + std::string(name)}) {
      const auto out = dir / "out";
      const ProcessResult r = runHaif(form + " --out '" + out.string() + "'", dir);
      EXPECT_EQ(r.exitCode, 0) << "haif " << form << ": " << r.err;
      EXPECT_EQ(r.out.rfind(std::string("  ") + name + " ", 0), 0u) << "haif " << form << " starts with its own line:\n" << r.out;
      EXPECT_NE(r.out.find(option), std::string::npos) << "haif " << form << " lists " << option << ":\n" << r.out;
      // One command's part only: no other command's line.
      for (const auto& [other, unused] : commands) {
        if (std::string(other) == name) continue;
        EXPECT_EQ(r.out.find(std::string("\n  ") + other + " "), std::string::npos) << form;
      }
      EXPECT_FALSE(std::filesystem::exists(out)) << "haif " << form << " must not run the command";
    }
  }
  const ProcessResult unknown = runHaif("help nosuchcommand", dir);
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("unknown command 'nosuchcommand'"), std::string::npos) << unknown.err;
  const ProcessResult all = runHaif("help", dir);
  EXPECT_EQ(all.exitCode, 0);
  for (const auto& [name, unused] : commands) EXPECT_NE(all.out.find(std::string("\n  ") + name), std::string::npos) << name;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace haif::test
