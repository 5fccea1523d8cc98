// The library used while a program's globals are being initialised: the deformer
// registry is built on first use, so a global in another file may read it (under
// AddressSanitizer's initialisation-order check, a registry of globals was a finding).
#include <string>

#include <gtest/gtest.h>

#include "finflex/deformer_type.hpp"
#include "finflex/rig.hpp"

namespace finflex {
namespace {

const std::string kNamesAtStartUp = deformer_type_names();
const StageSpec kStageAtStartUp = make_stage("hinge", "fin_angle");

TEST(StaticInitialisation, TheDeformerRegistryIsReadyForOtherGlobals) {
  EXPECT_EQ(kNamesAtStartUp, "\"bend\", \"hinge\" or \"spine\"");
  ASSERT_NE(kStageAtStartUp.deformer, nullptr);
  EXPECT_EQ(std::string(kStageAtStartUp.deformer->name), "hinge");
  EXPECT_EQ(kStageAtStartUp.deformer->options.size(), 1u);
}

}  // namespace
}  // namespace finflex
