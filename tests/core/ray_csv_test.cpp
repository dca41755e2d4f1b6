// The ray file of `prism trace` read from text (prism/ray_csv.hpp). The
// command-line tests (tests/cli) check the same through the binary; these
// pin down values and whole messages, and the fuzzers' regressions.
#include "prism/ray_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "prism/cancel.hpp"

namespace prism {
namespace {

// The message of the InputError that parsing `text` throws ("" when none).
std::string error_of(const std::string& text) {
  try {
    parse_ray_csv(text, "rays.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RayCsv, ReadsRaysWithHeaderTminBlankLinesAndCrlf) {
  auto rays = parse_ray_csv("ox,oy,oz,dx,dy,dz,tmin\r\n0,0,-5,0,0,2\r\n\r\n \t\n1, 2 ,3,0,-3,4,0.5\n", "rays.csv");
  ASSERT_EQ(rays.size(), 2u);
  EXPECT_EQ(rays[0].origin, glm::dvec3(0, 0, -5));
  EXPECT_EQ(rays[0].dir, glm::dvec3(0, 0, 1));
  EXPECT_EQ(rays[0].tmin, 0.0);
  EXPECT_EQ(rays[1].origin, glm::dvec3(1, 2, 3));
  EXPECT_EQ(rays[1].dir, glm::dvec3(0, -0.6, 0.8));
  EXPECT_EQ(rays[1].tmin, 0.5);
}

// A line of 1024 characters (and a '\r') is read; longer is refused (/dev/zero has no newline).
TEST(RayCsv, LinesAreBoundedAt1024Characters) {
  const std::string ray = "0,0,-5,0,0,1";
  const std::string longest = ray + std::string(1024 - ray.size(), ' ');
  EXPECT_EQ(parse_ray_csv(longest + "\r\n", "rays.csv").size(), 1u);
  EXPECT_EQ(error_of(ray + "\n" + longest + "  \n"), "rays.csv:2: longer than 1024 characters");
  EXPECT_EQ(error_of(std::string(5000, '\0')), "rays.csv:1: longer than 1024 characters");
}

// A stop request is seen while the file is read (every 4096 lines), not
// only once the trace starts.
TEST(RayCsv, AStopRequestEndsTheReading) {
  std::string text;
  for (int i = 0; i < 5000; ++i) text += "0,0,-5,0,0,1\n";
  request_cancel(15);
  EXPECT_THROW(parse_ray_csv(text, "rays.csv"), Cancelled);
  clear_cancel();
  EXPECT_EQ(parse_ray_csv(text, "rays.csv").size(), 5000u);
}

TEST(RayCsv, EmptyTextHasNoRays) { EXPECT_TRUE(parse_ray_csv("", "rays.csv").empty()); }

TEST(RayCsv, BadLinesNameFileAndLine) {
  EXPECT_EQ(error_of("0,0,-5,0,0,1\n0,0,-5,0,0\n"),
            "rays.csv:2: expected ox,oy,oz,dx,dy,dz[,tmin], got 5 fields");
  EXPECT_EQ(error_of("0,0,-5,0,zero,1\n"), "rays.csv:1: 'zero' is not a number");
  EXPECT_EQ(error_of("0,0,,0,0,1\n"), "rays.csv:1: '' is not a number");
  EXPECT_EQ(error_of("0,0,-5,0,0,1,\n"), "rays.csv:1: empty field at the end");
  EXPECT_EQ(error_of("nan,0,-5,0,0,1\n"), "rays.csv:1: 'nan' is not a finite number");
  EXPECT_EQ(error_of("0,0,-5,1e999,0,1\n"), "rays.csv:1: '1e999' is not a finite number");
  EXPECT_EQ(error_of("1,2,3,0,0,0\n"), "rays.csv:1: the direction is zero");
  EXPECT_EQ(error_of("0,0,-5,0,0,1\nox,oy,oz,dx,dy,dz\n"), "rays.csv:2: 'ox' is not a number");
}

// strtod stops at a NUL byte: "1<NUL>x" was read as 1 (found reading the
// code). Control bytes show as \xNN: a NUL would end the message.
TEST(RayCsv, NulByteInsideAFieldIsNotANumber) {
  using namespace std::string_literals;
  EXPECT_EQ(error_of("0,0,-5,0,0,1\0x\n"s), "rays.csv:1: '1\\x00x' is not a number");
  EXPECT_EQ(error_of("0,0,-5,0,\x1b[31m,1\n"), "rays.csv:1: '\\x1b[31m' is not a number");
}

TEST(RayCsv, MissingFileIsNamed) {
  try {
    read_ray_csv("/nonexistent/rays.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/rays.csv: cannot open ray file");
  }
}

// Fuzzer regressions (tests/fuzz/regressions/ray_csv): directions whose
// squared length underflows or overflows a double. 1e-160 came back as
// (1.0000113, 0, 0), not a unit vector; 1e200 was refused as "zero".
TEST(RayCsv, TinyDirectionIsNormalized) {
  auto rays = parse_ray_csv("0,0,0,1e-160,0,0\n", "rays.csv");
  ASSERT_EQ(rays.size(), 1u);
  EXPECT_EQ(rays[0].dir, glm::dvec3(1, 0, 0));
  rays = parse_ray_csv("0,0,0,0,-3e-170,4e-170\n", "rays.csv");
  EXPECT_NEAR(rays[0].dir.y, -0.6, 1e-15);
  EXPECT_NEAR(rays[0].dir.z, 0.8, 1e-15);
}

TEST(RayCsv, HugeDirectionIsNormalized) {
  auto rays = parse_ray_csv("0,0,0,1e200,1e200,0\n", "rays.csv");
  ASSERT_EQ(rays.size(), 1u);
  EXPECT_NEAR(rays[0].dir.x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(rays[0].dir.y, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(rays[0].dir.z, 0.0);
}

TEST(RayCsv, SmallestDirectionIsNotZero) {
  auto rays = parse_ray_csv("0,0,0,0,0,-4.9e-324\n", "rays.csv");
  ASSERT_EQ(rays.size(), 1u);
  EXPECT_EQ(rays[0].dir, glm::dvec3(0, 0, -1));
}

}  // namespace
}  // namespace prism
