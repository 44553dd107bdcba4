// R parameters, expressions in addresses and IF/ELSE/ENDIF, FOR/ENDFOR,
// WHILE/ENDWHILE on the virtual Sinumerik.
#include "cncc/backends/sinumerik_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace cncc::backends::sinumerik {
namespace {

SinumerikRun runOk(const std::string& text) {
  SinumerikRun run = runSinumerikProgram(text);
  EXPECT_FALSE(run.error) << (run.error ? run.error->what() : "");
  return run;
}

std::string errorOf(const std::string& text) {
  SinumerikRun run = runSinumerikProgram(text);
  return run.error ? std::string(run.error->what()) : std::string("no error");
}

TEST(SinumerikParameters, ExpressionsInAddresses) {
  SinumerikRun run = runOk("R1=30 R2=R1/2+POT(2) ; comment\n"
                           "G0 X=R1*COS(60) Y=-R2 Z=SQRT(16)-ATAN2(1,1)/45\n"
                           "M30\n");
  ASSERT_EQ(run.moves.size(), 0u); // the first move only makes the axes known
  EXPECT_NEAR(run.start.x(), 15, 1e-9);
  EXPECT_NEAR(run.start.y(), -19, 1e-9);
  EXPECT_NEAR(run.start.z(), 3, 1e-9);
}

TEST(SinumerikParameters, ForLoopBoltCircleWithIfElse) {
  SinumerikRun run = runOk("G0 X0 Y0 Z5\n"
                           "R1=30 R2=4\n"
                           "FOR R3=0 TO R2-1\n"
                           "  G0 X=R1*COS(R3*360/R2) Y=R1*SIN(R3*360/R2)\n"
                           "  IF R3==2\n"
                           "    G1 Z-2 F100\n"
                           "  ELSE\n"
                           "    G1 Z-1 F100\n"
                           "  ENDIF\n"
                           "  G0 Z5\n"
                           "ENDFOR\n"
                           "M30\n");
  ASSERT_EQ(run.moves.size(), 12u);
  EXPECT_NEAR(run.moves[3].end.x(), 0, 1e-9);
  EXPECT_NEAR(run.moves[3].end.y(), 30, 1e-9);
  EXPECT_NEAR(run.moves[4].end.z(), -1, 1e-9);
  EXPECT_NEAR(run.moves[6].end.x(), -30, 1e-9);
  EXPECT_NEAR(run.moves[7].end.z(), -2, 1e-9); // the IF branch for R3 == 2
  EXPECT_NEAR(run.moves[10].end.z(), -1, 1e-9);
}

TEST(SinumerikParameters, WhileLoopAndAForThatDoesNotRun) {
  SinumerikRun run = runOk("G0 X0 Y0 Z0\nR5=0\nWHILE R5<3 AND NOT R5==7\nR5=R5+1\nENDWHILE\n"
                           "FOR R6=5 TO 1\nR5=100\nENDFOR\nG1 X=R5 F100\nM30\n");
  ASSERT_EQ(run.moves.size(), 1u);
  EXPECT_NEAR(run.moves[0].end.x(), 3, 1e-9);
}

TEST(SinumerikParameters, ErrorsNameTheLine) {
  EXPECT_NE(errorOf("G0 X0 Y0 Z0\nR1=1/0\nM30\n").find("line 2: division by zero"),
            std::string::npos);
  EXPECT_NE(errorOf("R400=1\nM30\n").find("R400 does not exist"), std::string::npos);
  EXPECT_NE(errorOf("IF R1>0\nM30\n").find("without its end"), std::string::npos);
  EXPECT_NE(errorOf("ENDIF\nM30\n").find("without its opening"), std::string::npos);
  EXPECT_NE(errorOf("FOR R1=0 TO 3\nIF R1>1\nENDFOR\nENDIF\nM30\n").find("cross"),
            std::string::npos);
  EXPECT_NE(errorOf("G0 X=FOO(1)\nM30\n").find("FOO"), std::string::npos);
  EXPECT_NE(errorOf("WHILE 1\nENDWHILE\nM30\n").find("step limit"), std::string::npos);
}

} // namespace
} // namespace cncc::backends::sinumerik
