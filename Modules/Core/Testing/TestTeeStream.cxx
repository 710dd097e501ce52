#include <vimlop/Core/TeeStream.h>

#include <gtest/gtest.h>

#include <sstream>

using namespace vimlop;

TEST(TeeStream, WritesEverythingToBothStreamsInOrder)
{
  std::ostringstream terminal;
  std::ostringstream file;
  TeeStream both(terminal, file);
  both << "vimlop register: " << 30 << " frames\n";
  both.put('x');
  both.write("yz", 2);
  both.flush();
  EXPECT_TRUE(both.good());
  EXPECT_EQ(terminal.str(), "vimlop register: 30 frames\nxyz");
  EXPECT_EQ(file.str(), terminal.str());
}

TEST(TeeStream, AFlushReportsAStreamThatFailed)
{
  std::ostringstream terminal;
  std::ostringstream broken;
  broken.setstate(std::ios::badbit);
  TeeStream both(terminal, broken);
  both << "line\n" << std::flush;
  EXPECT_EQ(terminal.str(), "line\n");
  EXPECT_TRUE(both.bad());
}
