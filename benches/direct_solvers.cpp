// Direct sparse solve of the differential-space reconstruction system with Eigen's
// SimplicialLDLT, for the side-by-side benchmark of scripts/bench_differential.py.
// Input: a .sys file from `cargo run --release --example differential_bench` (L_k as
// triplets, delta = 4^-k Delta_k, anchors with values, our solution). Forms
// N = L^T L + sum_a e_a e_a^T and b = L^T delta + sum_a e_a x_a, then times
// analyzePattern + factorize + solve (3 right-hand sides), and reports the relative residual
// ||b - N x||_F / ||b||_F and max |x_eigen - x_ours| / bbox diagonal.
// Build: g++ -O2 -DNDEBUG -I/usr/include/eigen3 benches/eigen_ldlt.cpp -o target/eigen_ldlt
#include <Eigen/Sparse>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

template <class T> static T rd(FILE *f) {
    T x;
    if (std::fread(&x, sizeof x, 1, f) != 1) { std::fprintf(stderr, "short file\n"); std::exit(2); }
    return x;
}

int main(int argc, char **argv) {
    if (argc != 2) { std::fprintf(stderr, "usage: eigen_ldlt FILE.sys\n"); return 2; }
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

    auto t0 = std::chrono::steady_clock::now();
    Eigen::SparseMatrix<double> L(n, n);
    L.setFromTriplets(t.begin(), t.end());
    Eigen::SparseMatrix<double> N = L.transpose() * L;
    Eigen::MatrixXd b = L.transpose() * delta;
    for (long k = 0; k < na; k++) {
        N.coeffRef(anchors[k], anchors[k]) += 1.0;
        b.row(anchors[k]) += av.row(k);
    }
    auto t1 = std::chrono::steady_clock::now();
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    ldlt.analyzePattern(N);
    auto t2 = std::chrono::steady_clock::now();
    ldlt.factorize(N);
    if (ldlt.info() != Eigen::Success) { std::fprintf(stderr, "factorization failed\n"); return 1; }
    auto t3 = std::chrono::steady_clock::now();
    Eigen::MatrixXd x = ldlt.solve(b);
    auto t4 = std::chrono::steady_clock::now();
    auto s = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    const double res = (b - N * x).norm() / b.norm();
    const double res_ours = (b - N * ours).norm() / b.norm();
    Eigen::Vector3d lo = x.colwise().minCoeff(), hi = x.colwise().maxCoeff();
    const double diff = (x - ours).cwiseAbs().maxCoeff() / (hi - lo).norm();
    std::printf("EIGEN n=%ld nnz(N)=%ld form=%.3f analyze=%.3f factorize=%.3f solve=%.3f "
                "ldlt_total=%.3f residual=%.2e ours_residual_same_system=%.2e "
                "max_diff_over_diag=%.2e ours_reconstruct=%.3f\n",
                n, (long)N.nonZeros(), s(t0, t1), s(t1, t2), s(t2, t3), s(t3, t4), s(t1, t4), res,
                res_ours, diff, ours_time);
    return 0;
}
