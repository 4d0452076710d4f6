// Direct sparse solves of the differential-space reconstruction system, for the side-by-side
// benchmark of scripts/bench_differential.py.
//
// Input: a .sys file from `cargo run --release --example differential_bench` (L_k as
// triplets, delta = 4^-k Delta_k, anchors with their values, our solution and our
// reconstruction time). The reconstruction is the least-squares problem
//
//     minimise ||L x - delta||^2 + sum_a ||x_a - v_a||^2            (seed 001 §3.2)
//
// solved here two ways, each column of x (three right-hand sides) at once:
//
//  * CHOLMOD supernodal Cholesky (SuiteSparse, METIS/AMD ordering; Eigen's CholmodSupport
//    front end) of the normal equations N x = b, N = L^T L + sum_a e_a e_a^T,
//    b = L^T delta + sum_a e_a v_a: the same system our conjugate-gradient solve works on,
//    by the strongest direct solver of it. Timed: analyse + factorise + solve (forming N
//    reported apart).
//  * SuiteSparseQR (sparse QR) of the stacked rectangular system [L; E] x = [delta; v]: the
//    least-squares solution without forming N, whose condition number is the square of
//    L's. It is the accuracy reference: each solution's distance to it is reported (over the
//    bounding-box diagonal), which the residual of the normal equations cannot bound.
//
// Run single-threaded (OPENBLAS_NUM_THREADS=1, OMP_NUM_THREADS=1: the script sets them), as
// our solve is. Build: g++ -O2 -DNDEBUG -I/usr/include/eigen3 -I/usr/include/suitesparse
//   benches/direct_solvers.cpp -lcholmod -lspqr -o target/direct_solvers
// `--no-qr` skips the QR reference (it needs much more memory than the Cholesky).
#include <Eigen/CholmodSupport>
#include <Eigen/SPQRSupport>
#include <Eigen/Sparse>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

template <class T> static T rd(FILE *f) {
    T x;
    if (std::fread(&x, sizeof x, 1, f) != 1) { std::fprintf(stderr, "short file\n"); std::exit(2); }
    return x;
}

using Clock = std::chrono::steady_clock;
static double secs(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

int main(int argc, char **argv) {
    if (argc < 2) { std::fprintf(stderr, "usage: direct_solvers FILE.sys [--no-qr]\n"); return 2; }
    const bool qr = !(argc > 2 && std::strcmp(argv[2], "--no-qr") == 0);
    FILE *f = std::fopen(argv[1], "rb");
    if (!f) { std::perror(argv[1]); return 2; }
    const long n = (long)rd<uint64_t>(f);
    const long nnz = (long)rd<uint64_t>(f);
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(nnz);
    for (long e = 0; e < nnz; e++) {
        uint32_t i = rd<uint32_t>(f), j = rd<uint32_t>(f);
        double v = rd<double>(f);
        t.emplace_back(i, j, v);
    }
    Eigen::MatrixXd delta(n, 3), ours(n, 3);
    for (long i = 0; i < n; i++) for (int a = 0; a < 3; a++) delta(i, a) = rd<double>(f);
    const long na = (long)rd<uint64_t>(f);
    std::vector<long> anchors(na);
    Eigen::MatrixXd av(na, 3);
    for (long k = 0; k < na; k++) anchors[k] = (long)rd<uint64_t>(f);
    for (long k = 0; k < na; k++) for (int a = 0; a < 3; a++) av(k, a) = rd<double>(f);
    for (long i = 0; i < n; i++) for (int a = 0; a < 3; a++) ours(i, a) = rd<double>(f);
    const double ours_time = rd<double>(f);
    std::fclose(f);

    // The normal equations.
    auto t0 = Clock::now();
    Eigen::SparseMatrix<double> L(n, n);
    L.setFromTriplets(t.begin(), t.end());
    Eigen::SparseMatrix<double> N = L.transpose() * L;
    Eigen::MatrixXd b = L.transpose() * delta;
    for (long k = 0; k < na; k++) {
        N.coeffRef(anchors[k], anchors[k]) += 1.0;
        b.row(anchors[k]) += av.row(k);
    }
    N.makeCompressed();
    auto t1 = Clock::now();
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> llt;
    llt.analyzePattern(N);
    auto t2 = Clock::now();
    llt.factorize(N);
    if (llt.info() != Eigen::Success) { std::fprintf(stderr, "CHOLMOD factorisation failed\n"); return 1; }
    auto t3 = Clock::now();
    Eigen::MatrixXd xc = llt.solve(b);
    auto t4 = Clock::now();
    const double res_c = (b - N * xc).norm() / b.norm();
    const double res_o = (b - N * ours).norm() / b.norm();
    Eigen::Vector3d lo = ours.colwise().minCoeff(), hi = ours.colwise().maxCoeff();
    const double diag = (hi - lo).norm();
    std::printf("CHOLMOD n=%ld nnz(N)=%ld form=%.3f analyze=%.3f factorize=%.3f solve=%.3f "
                "cholmod_total=%.3f cholmod_residual=%.2e ours_residual=%.2e "
                "ours_vs_cholmod=%.2e ours_reconstruct=%.3f\n",
                n, (long)N.nonZeros(), secs(t0, t1), secs(t1, t2), secs(t2, t3), secs(t3, t4),
                secs(t1, t4), res_c, res_o, (xc - ours).cwiseAbs().maxCoeff() / diag, ours_time);
    std::fflush(stdout);
    if (!qr) return 0;

    // The stacked least-squares system, by sparse QR.
    auto q0 = Clock::now();
    std::vector<Eigen::Triplet<double>> s(t);
    for (long k = 0; k < na; k++) s.emplace_back(n + k, anchors[k], 1.0);
    Eigen::SparseMatrix<double> A(n + na, n);
    A.setFromTriplets(s.begin(), s.end());
    A.makeCompressed();
    Eigen::MatrixXd rhs(n + na, 3);
    rhs.topRows(n) = delta;
    rhs.bottomRows(na) = av;
    Eigen::SPQR<Eigen::SparseMatrix<double>> spqr;
    spqr.setPivotThreshold(0.0);  // full column rank: no rank detection, the plain LS solution
    spqr.compute(A);
    if (spqr.info() != Eigen::Success) { std::fprintf(stderr, "SPQR failed\n"); return 1; }
    Eigen::MatrixXd xq = spqr.solve(rhs);
    auto q1 = Clock::now();
    std::printf("SPQR qr_total=%.3f qr_residual=%.2e ours_vs_qr=%.2e cholmod_vs_qr=%.2e\n",
                secs(q0, q1), (b - N * xq).norm() / b.norm(),
                (ours - xq).cwiseAbs().maxCoeff() / diag, (xc - xq).cwiseAbs().maxCoeff() / diag);
    return 0;
}
