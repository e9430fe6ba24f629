// [telemetry] config loading (table + partition) and its generated reference.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "process_util.hpp"
#include "visnav/telemetry/telemetry_params.hpp"

namespace visnav::telemetry {
namespace {

LoadError loadText(const std::string& text, TelemetryParams& params) {
  const std::string path = test::tempPath("telemetry-params") + ".toml";
  std::ofstream(path) << text;
  io::ConfigFile config;
  LoadError e = config.open(path);
  if (e.ok) e = applyTelemetryConfig(config, params);
  if (e.ok) e = config.checkNoUnknownKeys();
  return e;
}

TEST(TelemetryParams, DefaultsAndPartition) {
  const TelemetryParams p;
  EXPECT_TRUE(p.enabled);
  EXPECT_EQ(p.domain_id, 0);
  EXPECT_STREQ(p.partitionName(), kDefaultPartition);
  EXPECT_EQ(partitionProblem("visnav"), nullptr);
  EXPECT_NE(partitionProblem(""), nullptr);
  EXPECT_NE(partitionProblem("a*"), nullptr);  // a DDS wildcard would match other partitions
  EXPECT_NE(partitionProblem(std::string(64, 'a').c_str()), nullptr);
  EXPECT_EQ(partitionProblem(std::string(63, 'a').c_str()), nullptr);
}

TEST(TelemetryParams, LoadsTableAndPartition) {
  TelemetryParams p;
  const LoadError e = loadText(
      "[telemetry]\ndomain_id = 7\npartition = \"sat-2.test\"\ndeadline_periods = 2.0\ncommand_depth = 4\n",
      p);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(p.domain_id, 7);
  EXPECT_STREQ(p.partitionName(), "sat-2.test");
  EXPECT_DOUBLE_EQ(p.deadline_periods, 2.0);
  EXPECT_EQ(p.command_depth, 4);
}

TEST(TelemetryParams, RejectsBadValuesNamingTheKey) {
  TelemetryParams p;
  LoadError e = loadText("[telemetry]\ndomain_id = 300\n", p);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("domain_id"), std::string::npos) << e.message;
  e = loadText("[telemetry]\npartition = \"two words\"\n", p);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("partition"), std::string::npos) << e.message;
  e = loadText("[telemetry]\nparttion = \"x\"\n", p);  // typo: unknown key
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("parttion"), std::string::npos) << e.message;
  EXPECT_STREQ(p.partitionName(), kDefaultPartition);  // failed loads leave the params untouched
  EXPECT_EQ(p.domain_id, 0);
}

TEST(TelemetryParams, ReferenceListsEveryKey) {
  const std::string doc = telemetryParametersMarkdown();
  for (const char* key :
       {"enabled", "domain_id", "partition", "deadline_periods", "max_blocking_ms", "command_depth"})
    EXPECT_NE(doc.find(std::string("`[telemetry] ") + key + "`"), std::string::npos) << key;
}

// Issue 13 item 9: `partition = ""` is present and wrong; it used to fall back to the default silently.
TEST(TelemetryParams, EmptyOrNonStringPartitionIsAnError) {
  TelemetryParams p;
  LoadError e = loadText("[telemetry]\npartition = \"\"\n", p);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("must not be empty"), std::string::npos) << e.message;
  e = loadText("[telemetry]\npartition = 5\n", p);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("must be a string"), std::string::npos) << e.message;
  EXPECT_STREQ(p.partitionName(), kDefaultPartition);
}

}  // namespace
}  // namespace visnav::telemetry
