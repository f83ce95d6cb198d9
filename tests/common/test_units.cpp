#include <catch2/catch.hpp>

#include "common/units.hpp"

using xpl::ModelUnits;
using xpl::UNIT_SYSTEMS;

TEST_CASE("unit labels follow the stated system, token by token", "[common][units]") {
  const xpl::UnitSystem* mm = xpl::find_unit_system("mm-t-s");  // case-insensitive
  REQUIRE(mm != nullptr);
  CHECK(mm->name == "MM-T-S");
  CHECK(xpl::unit_in("Pa", *mm) == "MPa");
  CHECK(xpl::unit_in("m/s^2", *mm) == "mm/s^2");
  CHECK(xpl::unit_in("N m", *mm) == "N mm");
  CHECK(xpl::unit_in("J", *mm) == "mJ");
  CHECK(xpl::unit_in("rad/s", *mm) == "rad/s");  // radians are no unit of the system
  CHECK(xpl::unit_in("", *mm).empty());
  const xpl::UnitSystem* ms = xpl::find_unit_system("MM-KG-MS");
  REQUIRE(ms != nullptr);
  CHECK(xpl::unit_in("m/s", *ms) == "mm/ms");
  CHECK(xpl::unit_in("N m", *ms) == "kN mm");
  CHECK(xpl::unit_in("Pa", *ms) == "GPa");
  CHECK(xpl::find_unit_system("MM-T") == nullptr);
  CHECK(xpl::dimension_of("m/s^2") == "[length]/[time]^2");
  CHECK(xpl::dimension_of("Pa") == "[stress]");
}

TEST_CASE("every system is consistent: force = mass length / time^2", "[common][units]") {
  // The force, stress and energy labels must be what the base units make, in SI: checked
  // through the SI values of one unit of each (N, Pa, J of SI itself are 1).
  struct Derived {
    const char* name;
    double force_si, stress_si, energy_si;
  };
  const Derived derived[] = {
      {"SI", 1.0, 1.0, 1.0},       {"MM-T-S", 1.0, 1e6, 1e-3},
      {"MM-KG-MS", 1e3, 1e9, 1.0}, {"MM-G-MS", 1.0, 1e6, 1e-3},
      {"CGS", 1e-5, 0.1, 1e-7},    {"IN-LBF-S", 4.4482216152605, 6894.757293168, 0.1129848290276}};
  REQUIRE(std::size(derived) == UNIT_SYSTEMS.size());
  for (const Derived& d : derived) {
    const xpl::UnitSystem* s = xpl::find_unit_system(d.name);
    REQUIRE(s != nullptr);
    const double force = s->mass_si * s->length_si / (s->time_si * s->time_si);
    CHECK(force == Approx(d.force_si).epsilon(1e-8));  // the slinch is given to 9 digits
    CHECK(force / (s->length_si * s->length_si) == Approx(d.stress_si).epsilon(1e-8));
    CHECK(force * s->length_si == Approx(d.energy_si).epsilon(1e-8));
  }
}

TEST_CASE("a model's labels: stated, SI assumed, or dimensions only", "[common][units]") {
  ModelUnits units;
  CHECK(units.label("Pa") == "Pa");
  CHECK(units.system_name() == "SI (assumed)");
  CHECK(units.summary().find("SI assumed") != std::string::npos);
  units.stated = xpl::find_unit_system("MM-T-S");
  CHECK(units.label("Pa") == "MPa");
  CHECK(units.system_name() == "MM-T-S");
  CHECK(units.summary() == "length mm, mass t, time s, force N, stress MPa, energy mJ");
  units.stated = nullptr;
  units.dimensions_only = true;
  CHECK(units.label("Pa") == "[stress]");
  CHECK(units.label("J") == "[energy]");
  CHECK(units.system_name() == "unstated");
}
