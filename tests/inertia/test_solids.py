"""Primitive solids against textbook formulas, point clouds, meshes and each other."""

import numpy as np
import pytest

import kreisel as kr
from kreisel.inertia import primitive_meshes as meshes

I = kr.inertia


def diag(t):
    return np.diagonal(t, axis1=-2, axis2=-1)


# textbook table (e.g. Goldstein; Landau–Lifshitz §32), entered by hand for m = 2
TEXTBOOK = [
    ("box", (2.0, (1.0, 2.0, 3.0)), [13 / 6, 10 / 6, 5 / 6]),
    ("solid_sphere", (2.0, 3.0), [7.2, 7.2, 7.2]),
    ("hollow_sphere", (2.0, 3.0), [12.0, 12.0, 12.0]),
    ("hollow_sphere", (2.0, 2.0, 1.0), [0.8 * 31 / 7] * 3),
    ("solid_cylinder", (2.0, 1.0, 3.0), [2.0, 2.0, 1.0]),
    ("hollow_cylinder", (2.0, 1.0, 3.0), [2.5, 2.5, 2.0]),
    ("hollow_cylinder", (2.0, 2.0, 3.0, 1.0), [4.0, 4.0, 5.0]),
    ("solid_cone", (2.0, 1.0, 2.0), [0.6, 0.6, 0.6]),
    ("solid_cone", (2.0, 1.0, 2.0, "apex"), [5.1, 5.1, 0.6]),
    ("solid_cone", (2.0, 1.0, 2.0, "base"), [1.1, 1.1, 0.6]),
    ("solid_ellipsoid", (2.0, (1.0, 2.0, 3.0)), [5.2, 4.0, 2.0]),
    ("thin_rod", (2.0, 3.0), [1.5, 1.5, 0.0]),
    ("thin_disk", (2.0, 2.0), [2.0, 2.0, 4.0]),
    ("thin_ring", (2.0, 2.0), [4.0, 4.0, 8.0]),
    ("torus", (2.0, 2.0, 1.0), [5.25, 5.25, 9.5]),
]


@pytest.mark.parametrize("name, args, expected", TEXTBOOK, ids=[t[0] for t in TEXTBOOK])
def test_textbook_values(name, args, expected):
    tensor = getattr(I, name)(*args)
    np.testing.assert_allclose(diag(tensor), expected, rtol=1e-15, atol=0)
    np.testing.assert_array_equal(tensor - np.diag(diag(tensor)), 0.0)


def midpoint_grid(n):
    """Cell centres of an n³ grid on [-1/2, 1/2]³."""
    c = (np.arange(n) + 0.5) / n - 0.5
    return np.stack(np.meshgrid(c, c, c, indexing="ij"), axis=-1).reshape(-1, 3)


def test_box_against_point_grid_exactly():
    # the cell-centre grid has <x²> = a²/12 (1 − 1/n²) exactly
    size = np.array([1.0, 2.0, 3.0])
    n = 10
    pts = midpoint_grid(n) * size
    tensor = I.points(np.full(len(pts), 4.0 / len(pts)), pts)
    np.testing.assert_allclose(tensor, I.box(4.0, size) * (1.0 - 1.0 / n**2), rtol=1e-13, atol=1e-15)


@pytest.mark.parametrize(
    "name, args, inside",
    [
        ("solid_sphere", (1.5,), lambda p: (p**2).sum(1) <= 1.5**2),
        ("solid_ellipsoid", ((1.0, 1.5, 2.0),), lambda p: ((p / [1.0, 1.5, 2.0]) ** 2).sum(1) <= 1),
        ("solid_cylinder", (1.0, 3.0), lambda p: ((p[:, :2] ** 2).sum(1) <= 1) & (np.abs(p[:, 2]) <= 1.5)),
        ("hollow_sphere", (2.0, 1.2), lambda p: ((p**2).sum(1) <= 4) & ((p**2).sum(1) >= 1.44)),
        ("torus", (1.2, 0.8), lambda p: (np.hypot(p[:, 0], p[:, 1]) - 1.2) ** 2 + p[:, 2] ** 2 <= 0.64),
    ],
)
def test_solids_against_point_clouds(name, args, inside):
    # uniform grid over the bounding cube of side 4; a fine grid's error is O(h) at the
    # curved boundary, here below 0.3 %
    pts = midpoint_grid(120) * 4.0
    pts = pts[inside(pts)]
    mass = 3.0
    cloud = I.points(np.full(len(pts), mass / len(pts)), pts - pts.mean(axis=0))
    np.testing.assert_allclose(cloud, getattr(I, name)(mass, *args), rtol=3e-3, atol=3e-3 * np.abs(cloud).max())


def test_thin_bodies_against_point_sets():
    n = 7  # evenly spaced points on a circle reproduce a ring exactly for n >= 3
    phi = 2 * np.pi * np.arange(n) / n
    ring = np.stack([np.cos(phi), np.sin(phi), np.zeros(n)], axis=1) * 1.5
    np.testing.assert_allclose(I.points(np.full(n, 2.0 / n), ring), I.thin_ring(2.0, 1.5), atol=1e-15)
    # rod: cell centres along z, <z²> = L²/12 (1 − 1/n²)
    z = ((np.arange(50) + 0.5) / 50 - 0.5) * 3.0
    rod = np.stack([np.zeros(50), np.zeros(50), z], axis=1)
    np.testing.assert_allclose(I.points(np.full(50, 0.04), rod), I.thin_rod(2.0, 3.0) * (1 - 1 / 50**2), rtol=1e-13, atol=1e-16)


def test_thin_limits():
    np.testing.assert_allclose(I.solid_cylinder(2.0, 1.5, 0.0 + 1e-300), I.thin_disk(2.0, 1.5), rtol=1e-15)
    np.testing.assert_allclose(I.hollow_cylinder(2.0, 1.5, 1e-300), I.thin_ring(2.0, 1.5), rtol=1e-15)
    np.testing.assert_allclose(I.hollow_sphere(2.0, 1.5, 1.5 * (1 - 1e-12)), I.hollow_sphere(2.0, 1.5), rtol=1e-11)
    np.testing.assert_allclose(I.hollow_sphere(2.0, 1.5, 0.0), I.solid_sphere(2.0, 1.5), rtol=1e-15)
    np.testing.assert_allclose(I.box(2.0, (0.0, 0.0, 3.0)), I.thin_rod(2.0, 3.0), rtol=1e-15)
    np.testing.assert_allclose(I.solid_ellipsoid(2.0, (1.5, 1.5, 1.5)), I.solid_sphere(2.0, 1.5), rtol=1e-15)


def density_part(solid, volume, *args, density=1.0):
    mass = density * volume
    return I.MassProperties(mass, np.zeros(3), solid(mass, *args))


def test_shells_are_differences_of_solids():
    R, r = 2.0, 1.3
    outer = density_part(I.solid_sphere, 4 / 3 * np.pi * R**3, R)
    inner = density_part(I.solid_sphere, 4 / 3 * np.pi * r**3, r)
    shell = I.combine([outer, I.MassProperties(-inner.mass, inner.com, -inner.inertia)])
    np.testing.assert_allclose(shell.inertia, I.hollow_sphere(shell.mass, R, r), rtol=1e-14)
    h = 3.0
    outer = density_part(I.solid_cylinder, np.pi * R**2 * h, R, h)
    inner = density_part(I.solid_cylinder, np.pi * r**2 * h, r, h)
    tube = I.combine([outer, I.MassProperties(-inner.mass, inner.com, -inner.inertia)])
    np.testing.assert_allclose(tube.inertia, I.hollow_cylinder(tube.mass, R, h, r), rtol=1e-14)


def polygon_radius_squared(radius, n):
    """Effective r² of a regular n-gon of circumradius R: its polar moment per area is
    R² (2 + cos 2π/n)/6 (n triangles from the centre), against r²/2 for the disk."""
    return radius**2 * (2.0 + np.cos(2.0 * np.pi / n)) / 3.0


@pytest.mark.parametrize("n", [3, 7, 64])
def test_prism_and_pyramid_meshes_are_exact(n):
    # the n-gon prism/pyramid is a cylinder/cone of the polygon's effective radius
    R, h = 1.3, 2.1
    r_eff = np.sqrt(polygon_radius_squared(R, n))
    cylinder = I.from_mesh(*meshes.cylinder_mesh(R, h, n))
    np.testing.assert_allclose(cylinder.inertia, I.solid_cylinder(cylinder.mass, r_eff, h), rtol=1e-13, atol=1e-15)
    cone = I.from_mesh(*meshes.cone_mesh(R, h, n))
    np.testing.assert_allclose(cone.com, [0, 0, h / 4], atol=1e-15)
    np.testing.assert_allclose(cone.inertia, I.solid_cone(cone.mass, r_eff, h), rtol=1e-13, atol=1e-15)
    r = 0.6
    tube = I.from_mesh(*meshes.cylinder_mesh(R, h, n, inner_radius=r))
    # the polygon factor scales both radii alike
    k = polygon_radius_squared(1.0, n)
    np.testing.assert_allclose(
        tube.inertia, I.hollow_cylinder(tube.mass, R * np.sqrt(k), h, r * np.sqrt(k)), rtol=1e-13, atol=1e-15
    )


@pytest.mark.parametrize(
    "make_mesh, solid",
    [
        (lambda n: meshes.ellipsoid_mesh((1.0, 1.5, 2.0), n, 2 * n), lambda m: I.solid_ellipsoid(m, (1.0, 1.5, 2.0))),
        (lambda n: meshes.torus_mesh(1.0, 0.4, 2 * n, n), lambda m: I.torus(m, 1.0, 0.4)),
        (lambda n: meshes.cylinder_mesh(1.0, 2.0, 4 * n), lambda m: I.solid_cylinder(m, 1.0, 2.0)),
    ],
    ids=["ellipsoid", "torus", "cylinder"],
)
def test_meshes_converge_at_second_order(make_mesh, solid):
    errors = []
    for n in (16, 32, 64):
        p = I.from_mesh(*make_mesh(n))
        errors.append(np.abs(p.inertia - solid(p.mass)).max() / np.abs(p.inertia).max())
    assert errors[-1] < 2e-3
    for coarse, fine in zip(errors, errors[1:]):
        assert 3.5 < coarse / fine < 4.5  # O(h²)


def test_broadcasting():
    masses = np.array([1.0, 2.0])[:, None]
    radii = np.array([0.5, 1.0, 2.0])
    out = I.solid_cylinder(masses, radii, 3.0)
    assert out.shape == (2, 3, 3, 3)
    np.testing.assert_allclose(out[1, 2], I.solid_cylinder(2.0, 2.0, 3.0))
    sizes = np.arange(1.0, 13.0).reshape(4, 3)
    np.testing.assert_allclose(I.box(2.0, sizes)[3], I.box(2.0, sizes[3]))


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: I.box(-1.0, (1, 1, 1)), "mass must be > 0"),
        (lambda: I.box(1.0, (1, -1, 1)), "size must be >= 0"),
        (lambda: I.box(1.0, (1, 1)), r"size must have shape \(\.\.\., 3\)"),
        (lambda: I.solid_sphere(1.0, 0.0), "radius must be > 0"),
        (lambda: I.solid_sphere(np.nan, 1.0), "mass must be finite"),
        (lambda: I.hollow_sphere(1.0, 1.0, 2.0), "inner_radius must not exceed radius"),
        (lambda: I.hollow_cylinder(1.0, 1.0, 1.0, -0.5), "inner_radius must be >= 0"),
        (lambda: I.solid_cone(1.0, 1.0, 1.0, about="tip"), "about must be one of"),
        (lambda: I.torus(1.0, 1.0, 1.5), "minor_radius must not exceed major_radius"),
        (lambda: I.thin_rod(1.0, -2.0), "length must be > 0"),
        (lambda: I.solid_ellipsoid(1.0, (1.0, 0.0, 1.0)), "semi_axes must be > 0"),
    ],
)
def test_refusals(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_refuses_non_numeric():
    with pytest.raises(TypeError, match="radius"):
        I.solid_sphere(1.0, "big")


def _scaled(args, mass_scale, length_scale):
    """Textbook arguments with the mass and every length multiplied (the keyword ``about`` kept)."""
    mass, *rest = args
    return (mass * mass_scale, *(r if isinstance(r, str) else np.multiply(r, length_scale) for r in rest))


@pytest.mark.parametrize("name, args, expected", TEXTBOOK, ids=[t[0] for t in TEXTBOOK])
def test_extreme_sizes_give_the_exact_moments_or_an_out_of_range_refusal(name, args, expected):
    # I = μ s² I(m, lengths) for mass × μ and lengths × s: each rounded exact value (mpmath) where it is
    # representable, else a refusal saying so; squaring s ~ 1e160 alone would overflow on the way
    mpmath = pytest.importorskip("mpmath")
    for mass_scale, length_scale in [(1e-250, 1e160), (1e250, 1e-160), (1.0, 1e-170), (1.0, 1e155),
                                     (1e300, 1e-5), (1e-300, 1e5)]:
        exact = [mpmath.mpf(e) * mpmath.mpf(mass_scale) * mpmath.mpf(length_scale) ** 2 for e in expected]
        call = lambda: getattr(I, name)(*_scaled(args, mass_scale, length_scale))  # noqa: E731
        if max(exact) > np.finfo(float).max:
            with pytest.raises(ValueError, match="out of range"):
                call()
            continue
        # 1e-15 (~4.5 ulp): the scaled mass and lengths are rounded before the call (up to 1.5 ulp once a
        # length is squared), then the moment takes about four rounded operations of its own
        np.testing.assert_allclose(diag(call()), [float(e) for e in exact], rtol=1e-15, atol=1e-321,
                                   err_msg=f"{name} with mass × {mass_scale:g}, lengths × {length_scale:g}")
