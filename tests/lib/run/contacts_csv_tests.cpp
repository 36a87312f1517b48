// contacts.csv's segment letters (lib/dem/run/contacts_csv.hpp): one per segment of a PRE face in the order
// of ξ_i, B / L / o / x for linked-bonded, linked-unbonded, open-bonded, open-broken; reversed when the
// contact is written from the other element's side. (The rows themselves: tests/outputs/check_contacts.py.)
#include <catch2/catch.hpp>

#include "dem/run/contacts_csv.hpp"

TEST_CASE("contacts.csv: one letter per face segment in the order of xi") {
  dem::Simulation::FaceSegments f;
  f.n = 4;
  auto set = [&](int k, int linked, int intact) {
    f.seg[static_cast<std::size_t>(k)].linked = static_cast<std::uint8_t>(linked);
    f.seg[static_cast<std::size_t>(k)].intact = static_cast<std::uint8_t>(intact);
  };
  set(0, 1, 1), set(1, 1, 0), set(2, 0, 1), set(3, 0, 0);
  CHECK(dem::segment_letters(f, false) == "BLox");
  CHECK(dem::segment_letters(f, true) == "xoLB");
  f.n = 0;  // a linear contact
  CHECK(dem::segment_letters(f, false).empty());
}

TEST_CASE("contacts.csv: the header names SI units and the sign convention's columns") {
  CHECK(dem::contacts_csv_header() == "step,t [s],i,j,wall,law,x [m],y [m],nx,ny,fn [N],fs [N],links,segments,mr [N*m]\n");
}
