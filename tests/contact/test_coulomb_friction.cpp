// contact/coulomb_friction.hpp: Coulomb's law against its closed form. Inside the cone
// |t| <= mu_s n the whole tangential motion goes (the fraction is 1); outside it, exactly
// mu_k n of the motion's length goes; without friction nothing does.
#include <doctest/doctest.h>

#include <massspring/contact/coulomb_friction.hpp>

TEST_CASE("Coulomb friction: stick inside the cone, lose mu_k n outside it") {
  using massspring::contact::coulomb_removed_fraction;
  // |t| = 0.3 under a normal of 1 with mu_s = 0.5: inside the cone, the point sticks.
  CHECK(coulomb_removed_fraction(0.09, 1.0, 0.5, 0.4) == 1.0);
  // On the cone's edge |t| = mu_s n it still sticks.
  CHECK(coulomb_removed_fraction(0.25, 1.0, 0.5, 0.4) == 1.0);
  // |t| = 2 outside the cone of 0.5: it slides and loses mu_k n = 0.4 of its length 2.
  const double slide = coulomb_removed_fraction(4.0, 1.0, 0.5, 0.4);
  CHECK(slide == doctest::Approx(0.2).epsilon(1e-15));
  CHECK(slide * 2.0 == doctest::Approx(0.4).epsilon(1e-15));
  // Static above kinetic: a motion just outside the static cone keeps more than it would have
  // lost at the static coefficient (the fraction drops from 1 to mu_k / mu_s).
  CHECK(coulomb_removed_fraction(0.2501, 1.0, 0.5, 0.25) == doctest::Approx(0.25 / 0.5001));
  // No friction: nothing goes, and no normal: nothing goes either.
  CHECK(coulomb_removed_fraction(1.0, 1.0, 0.0, 0.0) == 0.0);
  CHECK(coulomb_removed_fraction(1.0, 0.0, 0.5, 0.4) == 0.0);
  // Units cancel: the fraction of a velocity and of the same displacement over dt agree.
  const double dt = 1.0 / 30;
  CHECK(coulomb_removed_fraction(4.0, 1.0, 0.5, 0.4) ==
        doctest::Approx(coulomb_removed_fraction(4.0 * dt * dt, dt, 0.5, 0.4)).epsilon(1e-14));
}
