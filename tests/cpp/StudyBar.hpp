// One normal bar of the study's material, for the laws' tests: L0 = 0.02 m,
// A_n = 0.4 L0^2 (EA = 5.6e6 N), A_f = c_a L0^2, G_f = 100 N/m, eps_p = 6.3e-5.
#pragma once

struct StudyBar {
    double L = 0.02;
    double EA = 3.5e10 * 0.4 * 0.02 * 0.02;
    double Af = 0.1385 * 0.02 * 0.02;
    double Gf = 100.0;
    double epsP = 6.3e-5;
};
