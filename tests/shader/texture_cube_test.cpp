// Cube-map face selection, projection, derivatives and the seamless footprint (shader/texture_cube.h), checked
// against the spec's "Cube Map Face Selection" table and against the cube's geometry, not against the code's own
// output. The whole sampler is compared with lavapipe by cts texture.cube.*.
#include <gtest/gtest.h>

#include <cmath>

#include "shader/texture_cube.h"

using namespace tilevk::shader::cube;

namespace {

// The spec's table: major axis direction -> face, sc, tc, ma.
struct SpecFace {
    uint32_t face;
    double sc, tc, ma;
};
SpecFace spec_face(double x, double y, double z) {
    const double ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    if (az >= ax && az >= ay) return z >= 0 ? SpecFace{kPosZ, x, -y, az} : SpecFace{kNegZ, -x, -y, az};
    if (ay >= ax) return y >= 0 ? SpecFace{kPosY, x, z, ay} : SpecFace{kNegY, x, -z, ay};
    return x >= 0 ? SpecFace{kPosX, -z, -y, ax} : SpecFace{kNegX, z, -y, ax};
}

// The direction of face coordinates (s, t) on `face`: the table inverted (ma = 1).
void direction_of(uint32_t face, double s, double t, double dir[3]) {
    const double sc = 2 * s - 1, tc = 2 * t - 1;
    switch (face) {
        case kPosX:
            dir[0] = 1, dir[1] = -tc, dir[2] = -sc;
            return;
        case kNegX:
            dir[0] = -1, dir[1] = -tc, dir[2] = sc;
            return;
        case kPosY:
            dir[0] = sc, dir[1] = 1, dir[2] = tc;
            return;
        case kNegY:
            dir[0] = sc, dir[1] = -1, dir[2] = -tc;
            return;
        case kPosZ:
            dir[0] = sc, dir[1] = -tc, dir[2] = 1;
            return;
        default:
            dir[0] = -sc, dir[1] = -tc, dir[2] = -1;
            return;
    }
}

}  // namespace

// Directions whose s and t are exact in float: every face, both signs.
TEST(ShaderTextureCube, FaceAndCoordinatesFollowTheSpecTable) {
    const float dirs[][3] = {{2, 1, 0.5f}, {-2, 1, 0.5f}, {0.5f, 2, -1}, {0.5f, -2, -1}, {1, -0.5f, 4}, {1, -0.5f, -4},
                             {4, 3, -2},   {-4, -3, 2},   {0.25f, 1, 0}, {-1, 0.5f, 2},  {0, 0, 8},     {0, -8, 0}};
    for (const auto& d : dirs) {
        const SpecFace want = spec_face(d[0], d[1], d[2]);
        const FaceCoord got = lookup(d[0], d[1], d[2]);
        EXPECT_EQ(got.face, want.face) << d[0] << " " << d[1] << " " << d[2];
        EXPECT_EQ(double(got.s), 0.5 * (want.sc / want.ma + 1)) << d[0] << " " << d[1] << " " << d[2];
        EXPECT_EQ(double(got.t), 0.5 * (want.tc / want.ma + 1)) << d[0] << " " << d[1] << " " << d[2];
    }
}

// Ties go to z, then y (lp_build_cube_lookup's selects); a zero direction lands on +Z's centre (0.5 / 0 -> 0).
TEST(ShaderTextureCube, TiesPreferZThenY) {
    EXPECT_EQ(lookup(1, 1, 1).face, kPosZ);
    EXPECT_EQ(lookup(-1, 1, -1).face, kNegZ);
    EXPECT_EQ(lookup(1, -1, 0.5f).face, kNegY);
    EXPECT_EQ(lookup(-1, 1, 0).face, kPosY);
    const FaceCoord zero = lookup(0, 0, 0);
    EXPECT_EQ(zero.face, kPosZ);
    EXPECT_EQ(zero.s, 0.5f);
    EXPECT_EQ(zero.t, 0.5f);
}

// The derivative path gives the same face and coordinates, and derivatives that match the exact derivative of
// s = (sc / |ma| + 1) / 2 along the direction's derivative (to float precision) — negated on the negative faces:
// gallivm divides by the signed ma there (only their squares reach the LOD, so the sign never shows).
TEST(ShaderTextureCube, DerivativesAreThoseOfTheProjection) {
    const float dirs[][3] = {{0.9f, 0.3f, -0.2f}, {-0.4f, 1.1f, 0.35f}, {0.1f, -0.2f, -1.3f}, {0.7f, -0.9f, 0.1f}};
    const float ddx[3] = {0.013f, -0.021f, 0.008f}, ddy[3] = {-0.004f, 0.011f, 0.017f};
    for (const auto& d : dirs) {
        FaceDerivs fd;
        const FaceCoord a = lookup(d[0], d[1], d[2]);
        const FaceCoord b = lookup_with_derivs(d[0], d[1], d[2], ddx, ddy, &fd);
        EXPECT_EQ(a.face, b.face);
        EXPECT_NEAR(a.s, b.s, 1e-7);
        EXPECT_NEAR(a.t, b.t, 1e-7);
        const auto st = [&](const float* step, double h, double* s, double* t) {
            const SpecFace f = spec_face(d[0] + h * step[0], d[1] + h * step[1], d[2] + h * step[2]);
            *s = 0.5 * (f.sc / f.ma + 1), *t = 0.5 * (f.tc / f.ma + 1);
        };
        const double h = 1e-4;
        const double sign = (a.face & 1) ? -1.0 : 1.0;
        fd.dsdx = float(fd.dsdx * sign), fd.dtdx = float(fd.dtdx * sign);
        fd.dsdy = float(fd.dsdy * sign), fd.dtdy = float(fd.dtdy * sign);
        double s1, t1, s0, t0;
        st(ddx, h, &s1, &t1), st(ddx, -h, &s0, &t0);
        EXPECT_NEAR(fd.dsdx, (s1 - s0) / (2 * h), 1e-5);
        EXPECT_NEAR(fd.dtdx, (t1 - t0) / (2 * h), 1e-5);
        st(ddy, h, &s1, &t1), st(ddy, -h, &s0, &t0);
        EXPECT_NEAR(fd.dsdy, (s1 - s0) / (2 * h), 1e-5);
        EXPECT_NEAR(fd.dtdy, (t1 - t0) / (2 * h), 1e-5);
    }
}

// A texel past an edge is the neighbouring face's texel that a direction just past that edge lands in: every face,
// edge and texel along it, sizes 1, 2, 5 and 8.
TEST(ShaderTextureCube, TexelsPastAnEdgeAreTheNeighbouringFacesTexels) {
    for (int32_t n : {1, 2, 5, 8}) {
        const double eps = 1e-4;
        for (uint32_t face = 0; face < 6; ++face)
            for (int edge = 0; edge < 4; ++edge)
                for (int32_t i = 0; i < n; ++i) {
                    const double along = (i + 0.5) / n;
                    double s = along, t = along;
                    int32_t x = i, y = i;
                    if (edge == 0) s = -eps, x = -1;
                    if (edge == 1) s = 1 + eps, x = n;
                    if (edge == 2) t = -eps, y = -1;
                    if (edge == 3) t = 1 + eps, y = n;
                    double dir[3];
                    direction_of(face, s, t, dir);
                    const SpecFace f = spec_face(dir[0], dir[1], dir[2]);
                    const int32_t wx = int32_t(std::floor(0.5 * (f.sc / f.ma + 1) * n));
                    const int32_t wy = int32_t(std::floor(0.5 * (f.tc / f.ma + 1) * n));
                    const Texel got = across_edge(face, edge, x, y, n - 1);
                    EXPECT_EQ(got.face, f.face) << "face " << face << " edge " << edge << " i " << i << " n " << n;
                    EXPECT_EQ(got.x, wx) << "face " << face << " edge " << edge << " i " << i << " n " << n;
                    EXPECT_EQ(got.y, wy) << "face " << face << " edge " << edge << " i " << i << " n " << n;
                }
    }
}

// Inside a face the footprint is the plain 2x2 one; next to an edge its outside texels come from the neighbour;
// at a corner the missing texel is marked.
TEST(ShaderTextureCube, FootprintInsideAtAnEdgeAndAtACorner) {
    const Footprint in = footprint(kPosZ, 0.5f, 0.375f, 4);  // u = 1.5, v = 1.0
    EXPECT_EQ(in.texel[0].x, 1);
    EXPECT_EQ(in.texel[0].y, 1);
    EXPECT_EQ(in.texel[3].x, 2);
    EXPECT_EQ(in.texel[3].y, 2);
    EXPECT_EQ(in.ws, 0.5f);
    EXPECT_EQ(in.wt, 0.0f);
    for (const Texel& t : in.texel) EXPECT_EQ(t.face, uint32_t(kPosZ));
    for (bool c : in.corner) EXPECT_FALSE(c);

    const Footprint edge = footprint(kPosZ, 0.0625f, 0.5f, 4);  // u = -0.25: x0 = -1 falls off -x
    EXPECT_EQ(edge.ws, 0.75f);
    const Texel left = across_edge(kPosZ, 0, -1, 1, 3);
    EXPECT_EQ(edge.texel[0].face, left.face);
    EXPECT_EQ(edge.texel[0].x, left.x);
    EXPECT_EQ(edge.texel[0].y, left.y);
    EXPECT_EQ(edge.texel[1].face, uint32_t(kPosZ));
    for (bool c : edge.corner) EXPECT_FALSE(c);

    const Footprint corner = footprint(kNegY, 0.96875f, 0.03125f, 4);  // u = 3.375, v = -0.375: past +x and -y
    EXPECT_FALSE(corner.corner[0]);
    EXPECT_TRUE(corner.corner[1]);  // (x1, y0) is on neither neighbour
    EXPECT_FALSE(corner.corner[2]);
    EXPECT_FALSE(corner.corner[3]);
    EXPECT_EQ(corner.texel[0].face, across_edge(kNegY, 2, 3, -1, 3).face);
    EXPECT_EQ(corner.texel[3].face, across_edge(kNegY, 1, 4, 0, 3).face);
}
