#include <vimlop/Core/TextFormat.h>

#include <gtest/gtest.h>

#include <string>

using namespace vimlop;

TEST(TextFormat, FormatsAsPrintfDoes)
{
  EXPECT_EQ(formatText("P1 %-6s %.3f mm, %d %%", "imlp", 0.12345, 7), "P1 imlp   0.123 mm, 7 %");
  EXPECT_EQ(formatText("%s", ""), "");
}

TEST(TextFormat, KeepsTextLongerThanAnyFixedBuffer)
{
  const std::string longText(5000, 'x');
  EXPECT_EQ(formatText("<%s>", longText.c_str()), "<" + longText + ">");
}

TEST(TextFormat, EscapesTheCharactersHtmlGivesAMeaning)
{
  EXPECT_EQ(escapeHtml("a<b> & \"c\" 'd'"), "a&lt;b&gt; &amp; &quot;c&quot; 'd'");
  EXPECT_EQ(escapeHtml(""), "");
}

TEST(TextFormat, LowerCasesNamesAndTheExtensionsReadersTellFormatsBy)
{
  EXPECT_EQ(lowerCase("ProbeToTracker 25FPS"), "probetotracker 25fps");
  EXPECT_EQ(lowerCaseExtension("/data/Scope.IGS.MHA"), ".mha");
  EXPECT_EQ(lowerCaseExtension("ct.nii.gz"), ".gz");
  EXPECT_EQ(lowerCaseExtension("/data/frames"), "");
}
