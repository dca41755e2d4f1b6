// Progressive refinement (apps/prism/viewer/refinement.hpp): 1 spp after
// every change, doubling up to the scene's spp while still, then no render
// at all until the next change.
#include <gtest/gtest.h>

#include <vector>

#include "viewer/refinement.hpp"

namespace prism::viewer {
namespace {

// What a viewer loop without input renders over `turns` turns of the loop:
// the spp of each frame, in order.
std::vector<int> renders_while_still(Refinement& refinement, int turns) {
  std::vector<int> spps;
  for (int i = 0; i < turns; ++i) {
    if (auto spp = refinement.next_spp()) {
      refinement.rendered(*spp);
      spps.push_back(*spp);
    }
  }
  return spps;
}

TEST(Refinement, DoublesUpToTheScenesSppThenRendersNothing) {
  Refinement refinement(16);
  EXPECT_EQ(renders_while_still(refinement, 100), (std::vector<int>{1, 2, 4, 8, 16}));
  EXPECT_TRUE(refinement.done());
  EXPECT_EQ(refinement.shown_spp(), 16);
}

TEST(Refinement, LastStepStopsAtATargetThatIsNoPowerOfTwo) {
  Refinement refinement(12);
  EXPECT_EQ(renders_while_still(refinement, 100), (std::vector<int>{1, 2, 4, 8, 12}));
}

TEST(Refinement, OneSppSceneRendersOnceAndThenIdles) {
  Refinement refinement(1);
  EXPECT_EQ(renders_while_still(refinement, 1000), (std::vector<int>{1}));
  EXPECT_FALSE(refinement.next_spp().has_value());
}

TEST(Refinement, EveryFrameWhileMovingIsOneSpp) {
  Refinement refinement(64);
  for (int frame = 0; frame < 10; ++frame) {
    refinement.restart();  // the camera moved since the last frame
    ASSERT_EQ(refinement.next_spp(), 1);
    refinement.rendered(1);
  }
  // Stopped: 2, 4, ..., 64 follow.
  EXPECT_EQ(renders_while_still(refinement, 100), (std::vector<int>{2, 4, 8, 16, 32, 64}));
}

TEST(Refinement, AMoveAfterRefinementStartsAgainAtOneSpp) {
  Refinement refinement(4);
  EXPECT_EQ(renders_while_still(refinement, 10), (std::vector<int>{1, 2, 4}));
  refinement.restart();
  EXPECT_FALSE(refinement.done());
  EXPECT_EQ(refinement.shown_spp(), 0);
  EXPECT_EQ(renders_while_still(refinement, 10), (std::vector<int>{1, 2, 4}));
}

TEST(Refinement, ATargetBelowOneIsOne) {
  Refinement refinement(0);
  EXPECT_EQ(refinement.target_spp(), 1);
}

}  // namespace
}  // namespace prism::viewer
