// Dam-break surge front (Martin & Moyce 1952; Koshizuka & Oka 1996): the leading edge of the
// fluid along the floor, Z = x_front / a against T = t sqrt(2 g / a), compared with the digitised
// experiments in reference/dam_break_front.csv. The experiments lag simulations because
// the gate takes time to lift; a shift of the simulated T by +0.175 is the usual allowance and
// is applied explicitly by the caller (time_shift).
#pragma once

#include <string>
#include <vector>

#include "vrsph/particles/particles.hpp"

namespace vrsph {

// Largest coordinate along `axis` over fluid particles (the surge tip).
template <int D>
double surge_front(const ParticleSet<D>& ps, int axis = 0);

struct FrontPoint {
  double T = 0.0;
  double Z = 0.0;
};

// Rows of one source ("martin_moyce_1952", "koshizuka_oka_1996") of the reference file.
std::vector<FrontPoint> load_front_reference(const std::string& csv_path,
                                             const std::string& source);

struct FrontError {
  double rms = 0.0;
  double max_abs = 0.0;
  int n = 0;  // reference points inside the simulated range
};

// Compares a simulated front history (sorted by T) with reference points: the simulated Z is
// interpolated linearly at T_ref - time_shift; points outside the simulated range, or with
// T_ref < t_min, are skipped.
FrontError compare_front(const std::vector<FrontPoint>& sim, const std::vector<FrontPoint>& ref,
                         double time_shift, double t_min = 0.0);

}  // namespace vrsph
