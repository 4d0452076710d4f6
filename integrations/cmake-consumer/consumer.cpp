// The C ABI from C++17 against the static library: a circle from four control points with
// the Möbius interpolating curve scheme (every point stays on the unit circle).
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "nlsubdiv.h"

int main() {
    const double ctrl[] = {1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
    std::size_t len = 0, scratch = 0;
    if (nls_curve_refined_size(4, 1, 4, &len) != NLS_STATUS_OK) return 1;
    if (nls_curve_scratch_size(NLS_CURVE_MOBIUS_INTERPOLATING, 4, 1, 4, &scratch) != NLS_STATUS_OK) return 1;
    std::vector<double> out(3 * len), work(3 * scratch + 3);
    std::size_t n = 0;
    const nls_curve_view curve{ctrl, 4, 1};
    nls_status s = nls_curve_subdivide(NLS_CURVE_MOBIUS_INTERPOLATING, &curve, 4, out.data(), len, work.data(), scratch, &n, nullptr);
    if (s != NLS_STATUS_OK) {
        std::printf("consumer_static: %s\n", nls_status_str(s));
        return 1;
    }
    double worst = 0.0;
    for (std::size_t k = 0; k < n; ++k) worst = std::fmax(worst, std::fabs(std::hypot(out[3 * k], out[3 * k + 1]) - 1.0));
    // std::complex arithmetic pulls __muldc3 from the runtime: the static library must not break it.
    std::complex<double> z(0.6, 0.8), w = z * z;
    std::printf("consumer_static: %zu curve points, max |r-1| = %.1e, |z^2| = %.3f\n", n, worst, std::abs(w));
    return (n == len && worst < 1e-12 && std::fabs(std::abs(w) - 1.0) < 1e-15) ? 0 : 1;
}
