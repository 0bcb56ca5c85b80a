// The reference model's bending energy (docs/physics.md "Bending"), written out term by term:
// its force, or the Hessian's product with any field, and its energy.
#include "reference/reference.h"
#include "reference/vector_ops.h"

namespace ref {

// docs/physics.md "Bending": E = ½ Σ w_u(j)|D_u|² + ½ Σ w_v(i)|D_v|² + ½ Σ_cells t|T|², with
// w_u(j) = B·dv·s_j/du³, w_v(i) = B·du·s_i/dv³, t = 2B/(du·dv), s = ½ at a side's ends.
namespace {
double sideShare(int n, int count) {
    return n == 0 || n == count - 1 ? 0.5 : 1.0;
}
}  // namespace

void Simulation::addBending(const std::vector<V3>& w, std::vector<V3>& f,
                            bool pinnedColumns) const {
    const int nu = prm_.nu, nv = prm_.nv;
    if (prm_.bend == 0 || nu < 2 || nv < 2) return;
    const double du = prm_.sizeU / (nu - 1), dv = prm_.sizeV / (nv - 1);
    const V3 zero{0, 0, 0};
    auto at = [&](int i, int j) {
        const int k = j * nu + i;
        return pinned_[k] && !pinnedColumns ? zero : w[k];
    };
    auto push = [&](int i, int j, double c, const V3& d) {  // f −= c·d at (i, j)
        f[j * nu + i] = sub(f[j * nu + i], scale(c, d));
    };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            if (i >= 1 && i <= nu - 2) {  // the second difference along u centred at (i, j)
                const double wu = prm_.bend * dv * sideShare(j, nv) / (du * du * du);
                const V3 d = add(sub(at(i - 1, j), scale(2, at(i, j))), at(i + 1, j));
                push(i - 1, j, wu, d);
                push(i, j, -2 * wu, d);
                push(i + 1, j, wu, d);
            }
            if (j >= 1 && j <= nv - 2) {
                const double wv = prm_.bend * du * sideShare(i, nu) / (dv * dv * dv);
                const V3 d = add(sub(at(i, j - 1), scale(2, at(i, j))), at(i, j + 1));
                push(i, j - 1, wv, d);
                push(i, j, -2 * wv, d);
                push(i, j + 1, wv, d);
            }
            if (i <= nu - 2 && j <= nv - 2) {  // the twist of the cell at (i, j)
                const double t = 2 * prm_.bend / (du * dv);
                const V3 twist =
                    add(sub(sub(at(i, j), at(i + 1, j)), at(i, j + 1)), at(i + 1, j + 1));
                push(i, j, t, twist);
                push(i + 1, j, -t, twist);
                push(i, j + 1, -t, twist);
                push(i + 1, j + 1, t, twist);
            }
        }
}

double Simulation::bendingEnergy() const {
    // The energy of a quadratic form: ½ ⟨p, −F_b(p)⟩ (F_b is linear and vanishes on affine maps).
    std::vector<V3> f(p_.size(), V3{0, 0, 0});
    addBending(p_, f);
    double e = 0;
    for (std::size_t k = 0; k < p_.size(); ++k) e -= 0.5 * dot(p_[k], f[k]);
    return e;
}

}  // namespace ref
