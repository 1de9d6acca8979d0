// radchain::Session (radchain/batch/session.hpp) and the point engine under it, in process: what Python's Session
// binds, checked against the chain loaded and run by hand.
#include "radchain/batch/session.hpp"
#include "radchain/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace radchain {
namespace {

const std::string sensors = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/";

double solved_magnitude(const std::vector<Override>& overrides) {
  Chain chain = load_sensor(sensors + "msx-sbv.toml", overrides);
  return chain.run().value("target.magnitude").value();
}

// A value set in SI is the value a --set gives, and the solve runs again from it.
TEST(Session, SetInSiIsTheCommandLinesSet) {
  Session session(sensors + "msx-sbv.toml", std::nullopt, {});
  const double nominal = session.run().value("target.magnitude").value();
  EXPECT_NEAR(nominal, solved_magnitude({}), 1e-12);
  session.set_si("optics.aperture", 0.3);
  const double wide = session.run().value("target.magnitude").value();
  EXPECT_NEAR(wide, solved_magnitude({{"optics.aperture", "\"30 cm\""}}), 1e-9);
  EXPECT_GT(wide, nominal + 1);  // a 30 cm aperture sees fainter targets than the file's 15 cm
  EXPECT_DOUBLE_EQ(session.get("optics.aperture"), 0.3);
  EXPECT_EQ(session.si_unit("optics.aperture"), "m");
}

// A refused value (text or SI) leaves the session as it was.
TEST(Session, ARefusedValueChangesNothing) {
  Session session(sensors + "msx-sbv.toml", std::nullopt, {{"optics.aperture", "\"20 cm\""}});
  const double before = session.run().value("target.magnitude").value();
  EXPECT_THROW(session.set_text("optics.aperture", "\"-5 cm\""), InputError);
  EXPECT_THROW(session.set_si("optics.aperture", -0.05), InputError);
  EXPECT_THROW(session.set_si("optics.apertur", 0.05), InputError);
  ASSERT_EQ(session.overrides().size(), 1u);
  EXPECT_EQ(session.overrides()[0].value, "\"20 cm\"");
  EXPECT_EQ(session.run().value("target.magnitude").value(), before);
}

// Forward only is one run's choice: the next run solves again.
TEST(Session, ForwardOnlyKeepsTheSolvesForTheNextRun) {
  Session session(sensors + "msx-sbv.toml", std::nullopt, {});
  const Report forward = session.run(Solving::forward_only);
  EXPECT_TRUE(forward.solves.empty());
  const Report solved = session.run();
  ASSERT_EQ(solved.solves.size(), 1u);
  EXPECT_TRUE(solved.solves[0].converged);
  EXPECT_EQ(session.solved(), std::vector<std::string>{"target.magnitude"});
}

TEST(Session, AMistypedResultNamesTheNearest) {
  Session session(sensors + "msx-sbv.toml", std::nullopt, {});
  session.run();
  try {
    session.value("target.magnitud");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such result (did you mean \"target.magnitude\"?)"), std::string::npos)
        << e.what();
  }
}

// Points through the session: each point as the chain loaded with that value gives it; a failed solve names its
// point and leaves NaN in the solved column only there.
TEST(SessionPoints, EachPointIsTheChainsAndAFailureNamesItsPoint) {
  Session session(sensors + "msx-sbv.toml", std::nullopt, {});
  PointsEvaluator& points = session.points({"optics.aperture"}, {"target.magnitude", "detector.snr"}, false);
  const std::vector<double> apertures = {0.15, 1e-5, 0.2, 0.3, 0.25, 0.18, 0.16, 0.22, 0.4};  // one full group + one
  const double* values[] = {apertures.data()};
  const std::size_t n = apertures.size();
  std::vector<double> out(2 * n);
  std::vector<char> ok(n);
  std::string failure;
  EXPECT_EQ(points.run(values, n, out.data(), ok.data(), &failure), 1u);
  EXPECT_FALSE(ok[1]);
  EXPECT_TRUE(std::isnan(out[1]));
  EXPECT_EQ(failure.rfind("point 1 (optics.aperture = 1.0000000000000001e-05): the solve for target.magnitude failed: ",
                          0),
            0u)
      << failure;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == 1) continue;
    ASSERT_TRUE(ok[i]) << i;
    Chain chain = load_sensor(sensors + "msx-sbv.toml");
    chain.set("optics.aperture", apertures[i]);
    const Report report = chain.run();
    EXPECT_NEAR(out[i], report.value("target.magnitude").value(), 1e-9) << i;
    EXPECT_NEAR(out[n + i], report.value("detector.snr").value(), 1e-8) << i;
  }
  // The same job again reuses the evaluator; a set value makes a new one, built on it.
  EXPECT_EQ(&session.points({"optics.aperture"}, {"target.magnitude", "detector.snr"}, false), &points);
}

// A point the chain refuses is an InputError naming the point (Python raises it as radchain.InputError).
TEST(SessionPoints, APointPastTheHorizonIsNamed) {
  Session session(sensors + "worldview-2-pan-20deg.toml", std::nullopt, {});
  PointsEvaluator& points = session.points({"platform.roll"}, {"criteria.gsd.gsd_geometric_mean"}, false);
  const std::vector<double> rolls = {0.0, 80 * M_PI / 180};
  const double* values[] = {rolls.data()};
  std::vector<double> out(2);
  std::vector<char> ok(2);
  try {
    points.run(values, 2, out.data(), ok.data());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.context().rfind("point 1 (platform.roll = 1.3962634015954636), platform (plugin \"earth_orbit\")", 0), 0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("misses the Earth"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace radchain
