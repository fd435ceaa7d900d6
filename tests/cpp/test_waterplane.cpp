// Waterplane moments, metacentres and trim of fl::hydrostatics against a box barge, whose
// values are closed-form: I_T = L B^3 / 12, I_L = B L^3 / 12, KMt = B^2 / 12T + T / 2, and
// under a trim t (linear draft) LCB = L/2 - t L / (12 T).
#include <cmath>

#include <gtest/gtest.h>

#include "fairlines/errors.hpp"
#include "fairlines/hydrostatics.hpp"

namespace fairlines {
namespace {

constexpr double kL = 100.0, kB = 20.0, kD = 10.0;

// u from the deck edge down the side to the bilge corner and in to the keel, v along x.
NurbsSurface box_barge() {
  Eigen::MatrixXd P(6, 3);
  P << 0, kB / 2, kD, kL, kB / 2, kD, 0, kB / 2, 0, kL, kB / 2, 0, 0, 0, 0, kL, 0, 0;
  Eigen::VectorXd ku(5), kv(4);
  ku << 0, 0, 0.5, 1, 1;
  kv << 0, 0, 1, 1;
  return NurbsSurface(1, 1, ku, kv, 3, 2, P);
}

TEST(Waterplane, BoxBargeMomentsAndMetacentres) {
  for (double T : {1.0, 5.0, 10.0}) {
    const Hydrostatics h = hydrostatics(box_barge(), T);
    EXPECT_NEAR(h.inertia_t, kL * kB * kB * kB / 12, 1e-12 * kL * kB * kB * kB);
    EXPECT_NEAR(h.inertia_l, kB * kL * kL * kL / 12, 1e-12 * kB * kL * kL * kL);
    EXPECT_NEAR(h.kmt, kB * kB / (12 * T) + T / 2, 1e-12 * h.kmt);
    EXPECT_NEAR(h.tpc, 1.025 * kL * kB / 100, 1e-12 * h.tpc);
  }
}

TEST(Waterplane, TrimByTheSternIsALinearDraft) {
  HydrostaticsOptions o;
  o.trim = 1.0;
  o.trim_length = kL;
  const Hydrostatics h = hydrostatics(box_barge(), 5.0, o);
  EXPECT_NEAR(h.volume, kL * kB * 5.0, 1e-9);
  EXPECT_NEAR(h.lcb, kL / 2 - o.trim * kL / (12 * 5.0), 1e-10);
}

TEST(Waterplane, WaterplaneAboveTheTopIsRefused) {
  EXPECT_THROW(hydrostatics(box_barge(), kD + 0.5), InvalidInput);
  HydrostaticsOptions o;
  o.trim = 2.0;  // the AP end would go under
  o.trim_length = kL;
  EXPECT_THROW(hydrostatics(box_barge(), kD - 0.5, o), InvalidInput);
  o.trim_length = 0;
  EXPECT_THROW(hydrostatics(box_barge(), 5.0, o), InvalidInput);
}

}  // namespace
}  // namespace fairlines
