#include "dem/contact/face_contact.hpp"

namespace dem {

void start_face(const FaceLaw& law, const FaceConstants& c, double u0, bool bonded, bool geometric,
                FaceHistory& h) {
  h = FaceHistory{};
  h.geometric_start = geometric ? 1 : 0;
  const int n = law.segments;
  for (int i = 0; i < n; ++i) {
    SegmentState& s = h.seg[i];
    s.u = u0;
    s.intact = (bonded || law.healing) ? 1 : 0;
    // link: unlinked → linked when u(ξ) ≥ 0. A geometric start (the contact exists at t = 0 or forms
    // with the overlap onset) links every segment with P_e = K_n u0, u0 = overlap − this step's
    // increment, so that after the step P_e = K_n × overlap exactly as the disk law's e_n (a segment
    // still apart after the step then breaks at once, carrying nothing); so does a bonded face.
    if (u0 >= 0.0 || bonded || geometric) {
      s.linked = 1;
      s.pe = c.kn * u0;
    }
  }
}

}  // namespace dem
