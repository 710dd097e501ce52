#include <vimlop/Cohort/CohortManifest.h>
#include <vimlop/Cohort/CommandLineWords.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace vimlop
{
namespace
{

namespace fs = std::filesystem;

/// A manifest file `name` with `text`, in the running test's folder.
std::string manifestFile(const std::string& name, const std::string& text)
{
  static std::string folderOf;
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const fs::path folder = fs::path(VIMLOP_TEST_OUTPUT_DIR) / ("cohort-manifest-" + test);
  if (folderOf != test)
  {
    fixtures::freshTestFolder("cohort-manifest-" + test, false);
    folderOf = test;
  }
  const fs::path path = folder / name;
  std::ofstream(path) << text;
  return path.string();
}

/// What `vimlop` knows of `register`: --ct and --max-iterations take values,
/// --no-video is a flag.
CohortCommandCatalog registerOnly()
{
  CohortCommandCatalog catalog;
  catalog.commandKnown = [](const std::vector<std::string>& words)
  { return words == std::vector<std::string>{ "register" }; };
  catalog.optionKind = [](const std::vector<std::string>&, const std::string& name)
  {
    if (name == "no-video")
    {
      return CohortOptionKind::Flag;
    }
    return name == "ct" || name == "max-iterations" || name == "frames" ? CohortOptionKind::Value
                                                                        : CohortOptionKind::Unknown;
  };
  catalog.suggestion = [](const std::vector<std::string>&, const std::string& name)
  { return name == "cT" ? std::string("ct") : std::string(); };
  return catalog;
}

TEST(CohortManifest, ReadsACsvManifestWithOptionColumnsAndAnOptionsColumn)
{
  const std::string path = manifestFile("cohort.csv",
    "# a comment line\n"
    "id,command,ct,no-video,options\n"
    "case-1,register,ct/one.nii,true,--max-iterations 50\n"
    "\n"
    "case_2,register,\"ct/two, with a comma.nii\",false,\"--frames 'my frames'\"\n");
  const CohortManifest m = readCohortManifest(path, registerOnly());
  ASSERT_EQ(m.rows.size(), 2u);
  EXPECT_EQ(m.folder, fs::path(path).parent_path().string());
  EXPECT_EQ(m.rows[0].arguments(),
    (std::vector<std::string>{
      "register", "--ct", "ct/one.nii", "--no-video", "--max-iterations", "50" }));
  EXPECT_EQ(m.rows[0].line, 3);
  EXPECT_EQ(m.rows[1].arguments(),
    (std::vector<std::string>{
      "register", "--ct", "ct/two, with a comma.nii", "--frames", "my frames" }));
  EXPECT_EQ(m.rows[1].line, 5);
  EXPECT_EQ(m.find("case_2"), &m.rows[1]);
  EXPECT_EQ(m.find("case-3"), nullptr);
}

TEST(CohortManifest, ReadsAJsonManifestAsTheSameRows)
{
  const std::string csv = manifestFile("cohort.csv",
    "id,command,ct,no-video,options\ncase-1,register,ct/one.nii,true,--max-iterations 50\n");
  const std::string json = manifestFile("cohort.json",
    R"({"rows": [{"id": "case-1", "command": "register", "ct": "ct/one.nii", "no-video": true,
                  "options": {"max-iterations": 50}}]})");
  const CohortRow a = readCohortManifest(csv, registerOnly()).rows.at(0);
  const CohortRow b = readCohortManifest(json, registerOnly()).rows.at(0);
  EXPECT_EQ(a.arguments(), b.arguments());
  EXPECT_EQ(a.digest(), b.digest());
  // The options as an array of words, as on a command line.
  const std::string words = manifestFile("words.json",
    R"({"rows": [{"id": "a", "command": "register", "options": ["--max-iterations", "7", "--no-video"]}]})");
  EXPECT_EQ(readCohortManifest(words, registerOnly()).rows.at(0).arguments(),
    (std::vector<std::string>{ "register", "--max-iterations", "7", "--no-video" }));
}

TEST(CohortManifest, ARowsDigestChangesWithWhatItRunsOnly)
{
  CohortRow row;
  row.id = "a";
  row.command = { "register" };
  row.options = { { "ct", "x.nii" } };
  const std::string digest = row.digest();
  EXPECT_EQ(digest.size(), 64u);
  row.id = "b";
  row.line = 9;
  EXPECT_EQ(row.digest(), digest);
  row.options = { { "ct", "y.nii" } };
  EXPECT_NE(row.digest(), digest);
  // Two words are not one word with a blank.
  row.options = { { "ct", "x.nii --no-video" } };
  CohortRow other = row;
  other.options = { { "ct", "x.nii" }, { "no-video", "" } };
  EXPECT_NE(row.digest(), other.digest());
}

TEST(CohortManifest, RefusesBadRowsNamingTheFileTheLineAndTheRow)
{
  const auto refusal = [](const std::string& name, const std::string& text)
  {
    const std::string path = manifestFile(name, text);
    const std::string message =
      fixtures::errorMessageOf([&] { readCohortManifest(path, registerOnly()); });
    const std::string prefix = "'" + path + "'";
    return message.compare(0, prefix.size(), prefix) == 0 ? message.substr(prefix.size()) : message;
  };
  EXPECT_EQ(refusal("m.csv", "command,ct\nregister,x\n"),
    ", line 1: the header has no column 'id' (a manifest needs id and command)");
  EXPECT_EQ(refusal("m.csv", "id,command\n,register\n"), ", line 2: no id");
  EXPECT_EQ(refusal("m.csv", "id,command\na,register\na,register\n"),
    ", line 3 ('a'): the id is used by an earlier row");
  EXPECT_EQ(refusal("m.csv", "id,command\n../a,register\n"),
    ", line 2 ('../a'): an id is its output's folder name: letters, digits, '.', '_' and '-' "
    "only");
  EXPECT_EQ(refusal("m.csv", "id,command\na,regster\n"),
    ", line 2 ('a'): 'vimlop regster' is not a command a cohort can run (register, or evaluate "
    "synthetic|video|perturbation|warp|budget)");
  EXPECT_EQ(refusal("m.csv", "id,command,cT\na,register,x.nii\n"),
    ", line 2 ('a'): '--cT' is not an option of 'vimlop register'; did you mean '--ct'?");
  EXPECT_EQ(refusal("m.csv", "id,command,no-video\na,register,maybe\n"),
    ", line 2 ('a'): 'no-video' is a flag: give true or false, not 'maybe'");
  EXPECT_EQ(refusal("m.csv", "id,command,out\na,register,elsewhere\n"),
    ", line 2 ('a'): '--out' is the cohort's to set (each row writes its own output under the "
    "cohort folder, jobs/<id>)");
  EXPECT_EQ(refusal("m.csv", "id,command,options\na,register,--ct\n"),
    ", line 2 ('a'): '--ct' needs a value");
  EXPECT_EQ(refusal("m.csv", "id,command,options\na,register,ct x\n"),
    ", line 2 ('a'): 'ct' in the options is not an option (--name)");
  EXPECT_EQ(refusal("m.csv", "id,command\na,register,extra\n"),
    ", line 2 ('a'): 3 fields where the header has 2");
  EXPECT_EQ(
    refusal("m.csv", "id,command\n\"a,register\n"), ", line 2: a quoted field is not closed");
  EXPECT_EQ(refusal("m.csv", "# only a comment\n"),
    ": no header line (a manifest needs the columns id and command)");
  EXPECT_EQ(refusal("m.csv", "id,command\n"), ": no rows");
  EXPECT_EQ(
    refusal("m.json", "{\"rows\": 3}"), ": a JSON manifest is an object with an array \"rows\"");
  EXPECT_EQ(
    refusal("m.json", "{\"rows\": [{\"id\": \"a\", \"command\": \"register\", \"ct\": [1]}]}"),
    ", row 1 ('a'): 'ct' must be a string, a number or true/false");
  EXPECT_EQ(refusal("m.txt", "id,command\n"), ": a manifest is a .csv or .json file");
  EXPECT_EQ(fixtures::errorMessageOf([] { readCohortManifest("/no/such/manifest.csv"); }),
    "'/no/such/manifest.csv': no such file");
}

TEST(CohortManifest, SplitsAndJoinsCommandLinesAsAShellDoes)
{
  EXPECT_EQ(splitCommandLine("  --a 1\t--b 'two words' --c \"say \\\"hi\\\"\" x\\ y "),
    (std::vector<std::string>{ "--a", "1", "--b", "two words", "--c", "say \"hi\"", "x y" }));
  EXPECT_EQ(splitCommandLine("''"), (std::vector<std::string>{ "" }));
  EXPECT_EQ(fixtures::errorMessageOf([] { splitCommandLine("--a 'open"); }),
    "an unterminated single quote in '--a 'open'");
  const std::vector<std::string> words = { "vimlop", "--ct", "a b.nii", "it's", "", "x=1,2" };
  EXPECT_EQ(joinCommandLine(words), "vimlop --ct 'a b.nii' 'it'\\''s' '' x=1,2");
  EXPECT_EQ(splitCommandLine(joinCommandLine(words)), words);
}

} // namespace
} // namespace vimlop
