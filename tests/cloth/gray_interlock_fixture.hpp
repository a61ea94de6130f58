// gray-interlock's measured tables (Wang et al. 2011, as converted by ArcSim 0.3.1), built in
// code so that energy, lookup and simulator tests run without ../shared; the loader itself
// is tested against the shared file in test_material.cpp.
#pragma once

#include <drape/cloth/material.hpp>

namespace drape::test {

inline drape::cloth::Material gray_interlock_material() {
    drape::cloth::Material m;
    m.density_kg_per_m2 = 0.187;
    m.stretching_n_per_m = {{{16.593832, -14.695990, 34.477123, 36.860302},
                             {46.364765, 53.694656, 261.013855, -29.691301},
                             {49.285110, 87.596100, 206.373993, 22.768457},
                             {123.989220, 105.181770, 365.966217, 44.217571},
                             {139.686325, 73.592560, 413.553162, -174.43853},
                             {127.443810, 85.848587, 405.872833, 32.238411}}};
    m.bending_n_m = {{{23.191698e-6, 32.932217e-6, 34.406498e-6, 39.014420e-6, 23.382786e-6},
                      {24.749964e-6, 18.651314e-6, 16.370552e-6, 25.095791e-6, 8.860165e-6},
                      {14.267624e-6, 7.052906e-6, 14.515154e-6, 24.665127e-6, 19.383726e-6}}};
    return m;
}

}  // namespace drape::test
