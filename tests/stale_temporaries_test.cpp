// Which names are the server's temporaries, and whose: the startup sweep's rule.
#include <gtest/gtest.h>

#include "lightmass_server/control/stale_temporaries.h"

namespace lc::bake {
namespace {

TEST(StaleTemporaries, NamesTheOwnerOfEachKindOfTemporary) {
    EXPECT_EQ(temporary_owner("lightmass-bake-4242-7"), 4242);
    EXPECT_EQ(temporary_owner("lightmass-bake-4242-7.lcut"), 4242);
    EXPECT_EQ(temporary_owner("0123.scene.dump.tmp-99-0"), 99);
    EXPECT_EQ(temporary_owner("patches.ply.tmp-12-3"), 12);
}

TEST(StaleTemporaries, CompleteFilesAndOthersNamesAreNotTemporaries) {
    EXPECT_EQ(temporary_owner("0123.scene.dump"), std::nullopt);
    EXPECT_EQ(temporary_owner("lightmass-bake-notes.txt"), std::nullopt);
    EXPECT_EQ(temporary_owner("lightmass-bake-12"), std::nullopt);
    EXPECT_EQ(temporary_owner("lightmass-bake-12-3.lcut.bak"), std::nullopt);
    EXPECT_EQ(temporary_owner("report.tmp-x-1"), std::nullopt);
    EXPECT_EQ(temporary_owner(".tmp-5-1"), std::nullopt);
}

}  // namespace
}  // namespace lc::bake
