// The invariant checks (lightcuts/check.h): LC_CHECK stops the program naming
// the condition in every build; LC_DCHECK only where NDEBUG is not defined,
// and is not even evaluated elsewhere.
#include <gtest/gtest.h>

#include "lightcuts/check.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc {
namespace {

TEST(CheckDeathTest, ACheckThatFailsStopsNamingTheCondition) {
    const int two = 2;
    EXPECT_DEATH(LC_CHECK(two == 3), "check failed: two == 3");
    EXPECT_DEATH(LC_CHECK_INDEX(two, 2), "check failed");
    LC_CHECK(two == 2);  // holds: no effect
    LC_CHECK_INDEX(1, two);
}

TEST(Check, ADebugCheckIsEvaluatedOnlyInDebugBuilds) {
    int evaluations = 0;
    LC_DCHECK(++evaluations > 0);
#ifdef NDEBUG
    EXPECT_EQ(evaluations, 0);
#else
    EXPECT_EQ(evaluations, 1);
#endif
}

#ifndef NDEBUG
TEST(CheckDeathTest, TheWalkTreeChecksItsIndicesInDebugBuilds) {
    WalkTree tree;
    tree.nodes.resize(1);
    tree.nodes[0].representative = 5;  // no such leaf
    EXPECT_DEATH(tree.node(1), "check failed");
    EXPECT_DEATH(tree.light_of(0), "check failed");
}
#endif

}  // namespace
}  // namespace lc
