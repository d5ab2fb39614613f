// The explicit embedded Runge–Kutta pairs of the non-stiff path
// (component.h): 7 stages, first same as last (row 7 of A is b, c6 = c7 = 1),
// and a 4th-order continuous extension in the waveform's bubble form,
// x(θ) = Hermite cubic + θ²(1−θ)² h Σ d_i k_i (waveform.h).  Their order
// conditions are checked in tests/solver/explicit_pair_test.cc.
#pragma once

namespace asgard::solver {

struct ExplicitPair {
  double c[7];
  double a[7][7];  // row 6 (0-based) is the 5th-order solution's weights b
  double e[7];     // error estimate: 5th − 4th order weights
  double d[7];     // bubble of the continuous extension
};

// Dormand–Prince 5(4) (Dormand & Prince 1980; dense output coefficients of
// Hairer, Nørsett & Wanner, Solving ODEs I, II.6).
inline constexpr ExplicitPair kDormandPrince = {
    {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0},
    {{},
     {1.0 / 5},
     {3.0 / 40, 9.0 / 40},
     {44.0 / 45, -56.0 / 15, 32.0 / 9},
     {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
     {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
     {35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}},
    {71.0 / 57600, 0.0, -71.0 / 16695, 71.0 / 1920, -17253.0 / 339200, 22.0 / 525, -1.0 / 40},
    {-12715105075.0 / 11282082432, 0.0, 87487479700.0 / 32700410799, -10690763975.0 / 1880347072,
     701980252875.0 / 199316789632, -1453857185.0 / 822651844, 69997945.0 / 29380423}};

// Tsitouras 5(4) (Comput. Math. Appl. 62 (2011) 770–775): its 5th-order
// formula solved from the order conditions and the paper's free parameters;
// the embedded formula's scale and the continuous extension are our choices
// (core/solver/derive_tsitouras.py, which writes this table).
inline constexpr ExplicitPair kTsitouras = {
    {0.0, 0.16100000000000000, 0.32700000000000000, 0.90000000000000000, 0.98002554090450970,
     1.0000000000000000, 1.0000000000000000},
    {
        {},
        {0.16100000000000000},
        {-0.0084806554923569886, 0.33548065549235699},
        {2.8971530571054934, -6.3594484899750748, 4.3622954328695814},
        {5.3258648284392571, -11.748883564062829, 7.4955393428898369, -0.092495066361755269},
        {5.8614554429464202, -12.920969317847110, 8.1593678985761589, -0.071584973281401042,
         -0.028269050394068355},
        {0.096460766818065229, 0.010000000000000000, 0.47988965041449958, 1.3790085741037417,
         -3.2900695154360823, 2.3247105240997758},
    },
    {0.0016836670218115277, 0.00077224451695158809, -0.0074543213606489449, 0.13687844812316980,
     -0.55083677888520437, 0.43328817204283481, -0.014331431458914404},
    {-1.0591013765539141, 0.098942083711646547, 2.5172488981688896, -17.036936792648450,
     49.346724955348796, -36.418059598895751, 2.5511818308687829}};

}  // namespace asgard::solver
