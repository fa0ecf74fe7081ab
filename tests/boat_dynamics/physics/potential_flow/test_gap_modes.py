"""A catamaran's gap resonances as pole pairs, and the radiation memory fitted around them."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.physics.potential_flow.gap_modes import (
    MODE_MAX_ORDER,
    _block_error,
    _fit_block,
    band_mask,
    dof_blocks,
    fit_with_modes,
    memory_of,
    mode_excitation,
    mode_kernel,
    mode_memory,
    smooth_part,
)
from boat_dynamics.physics.potential_flow.hydro import (
    SHIPPED_COEFFICIENTS,
    GapMode,
    HydroFileError,
    froude_scaled,
    load_coefficients,
    moved,
    narrow_peaks,
)
from boat_dynamics.physics.potential_flow.radiation import RadiationMemory, fit_memory

OTTER = Path(__file__).resolve().parents[3] / "data" / "hydro" / "otter_box_pontoons.npz"
SHIPPED_OTTER = SHIPPED_COEFFICIENTS / "hull_2x1.04x0.4_d0.177_e884bec0fcfc08bc.npz"


@pytest.fixture(scope="module")
def otter():
    return load_coefficients(OTTER)


@pytest.fixture(scope="module")
def memory(otter):
    return fit_with_modes(otter)


def _errors_where(response: np.ndarray, hydro, keep: np.ndarray) -> tuple[float, float]:
    """Largest |B - B_file| and |A - A_file| at ``keep``, over each entry's file-wide scale."""
    bs = np.abs(np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)).max(axis=0)
    as_ = np.abs(np.diagonal(hydro.added_mass, axis1=1, axis2=2)).max(axis=0)
    w = hydro.omega[keep, None, None]
    b = np.abs(response[keep].real - hydro.radiation_damping[keep]).max(axis=0)
    a = np.abs(response[keep].imag / w - (hydro.added_mass[keep] - hydro.added_mass_inf))
    return (float((b / np.sqrt(np.outer(bs, bs))).max()),
            float((a.max(axis=0) / np.sqrt(np.outer(as_, as_))).max()))


def test_the_box_otters_memory_fits_its_file_within_5_percent_away_from_the_gap_modes(otter,
                                                                                       memory):
    """The box-pontoon Otter's file (shipped before the V pontoons, 0.078 m draft): outside
    omega0 +- 3 half-height widths of each of its 15 modes (11 of the 40 grid points), each
    entry's error over its largest value in the file. Measured (96 states): 4.4 %
    (B) and 3.8 % (A) there, 4.4 % at every point; the Hankel fit of the same file without its
    modes misses it by 80 %."""
    assert len(otter.gap_modes) == 15
    keep = ~band_mask(otter.omega, otter.gap_modes)
    assert keep.sum() == 29
    b, a = _errors_where(memory.response(otter.omega), otter, keep)
    assert b < 0.05 and a < 0.05, (b, a)
    assert memory.error < 0.06
    assert memory.poles.shape[0] <= MODE_MAX_ORDER
    assert np.all(memory.poles.real < 0.0)  # every state decays
    assert fit_memory(replace(otter, gap_modes=())).error > 0.5
    assert memory_of(otter).error == pytest.approx(memory.error)


def test_the_shipped_otters_memory_fits_its_file_within_5_percent_away_from_the_gap_modes():
    """Issue 32: the catamaran's radiation fit within 5 % of its file away from the gap
    resonance. The shipped Otter (V pontoons, 0.177 m draft, 17 modes), outside omega0 +- 3
    half-height widths of each mode, each entry's error over its largest value in the file.
    Measured: B 4.2 %, A 4.4 % there (the surge-pitch interference between the
    pontoons needs the 96 states: 64 give 5.8 % and 5.5 %)."""
    hydro = load_coefficients(SHIPPED_OTTER)
    memory = memory_of(hydro)
    assert len(hydro.gap_modes) == 17
    keep = ~band_mask(hydro.omega, hydro.gap_modes)
    assert keep.sum() >= 20
    b, a = _errors_where(memory.response(hydro.omega), hydro, keep)
    assert b < 0.05 and a < 0.05, (b, a)
    assert memory.poles.shape[0] <= MODE_MAX_ORDER
    assert np.all(memory.poles.real < 0.0)


@pytest.mark.parametrize("count", [6, 8, 10, 12, 14, 16])
def test_a_pair_that_relocates_onto_the_real_axis_stays_two_real_poles(count):
    """Vector fitting's relocation turned the shipped Otter's heave pair into two real poles
    with imaginary parts of +-1e-9 relative; each was then mirrored as if complex, and the
    heave fits with 6 to 16 poles missed the file by 1.8 to 1.4e7 (measured).
    Made real, they fit within 2.5 %."""
    hydro = load_coefficients(SHIPPED_OTTER)
    modes = mode_memory(hydro.gap_modes)
    of_modes = RadiationMemory(*modes, 0.0).response(hydro.omega)
    w = hydro.omega
    kernel = (hydro.radiation_damping + 1j * w[:, None, None]
              * (hydro.added_mass - hydro.added_mass_inf) - of_modes)
    scale = np.sqrt(np.abs(np.diagonal(hydro.radiation_damping, axis1=1, axis2=2)).max(axis=0))
    ascale = np.sqrt(np.abs(np.diagonal(hydro.added_mass, axis1=1, axis2=2)).max(axis=0))
    fit = _fit_block(w, kernel, [2], scale, ascale, count)
    assert _block_error(RadiationMemory(*fit, 0.0).response(w) + of_modes, hydro, [2]) < 0.025
    assert np.all(fit[0].real < 0.0)


def test_a_real_residue_is_a_lorentzian_whose_added_mass_follows_kramers_kronig():
    """B_m = rho (2 zeta w0 w)^2 / |D|^2 >= 0, A_m - A_inf = rho 2 zeta w0 (w0^2 - w^2) / |D|^2,
    |D|^2 = (w0^2 - w^2)^2 + (2 zeta w0 w)^2 (a parallel spring-mass-dashpot)."""
    rho = np.zeros((6, 6))
    rho[1, 1], rho[1, 3], rho[3, 1], rho[3, 3] = 900.0, 300.0, 300.0, 100.0
    mode = GapMode(8.0, 0.01, rho.astype(complex), np.zeros((2, 6), complex))
    w = np.array([2.0, 7.9, 8.0, 8.1, 15.0])
    k = mode_kernel((mode,), w)
    d2 = (64.0 - w**2) ** 2 + (0.16 * w) ** 2
    assert k[:, 1, 1].real == pytest.approx(900.0 * (0.16 * w) ** 2 / d2, rel=1e-12)
    assert k[:, 1, 1].imag / w == pytest.approx(900.0 * 0.16 * (64.0 - w**2) / d2, rel=1e-12)
    assert k[2, 1, 1].real == pytest.approx(900.0)  # B_m(omega0) = rho
    pair = RadiationMemory(*mode_memory((mode,)), 0.0).response(w)
    assert pair == pytest.approx(k, abs=1e-9)  # rank one: the pair is the mode exactly


def test_the_modes_explain_the_files_narrow_peaks(otter):
    kernel = mode_kernel(otter.gap_modes, otter.omega)
    smooth = smooth_part(otter)
    assert smooth.radiation_damping + kernel.real == pytest.approx(otter.radiation_damping)
    assert smooth.diffraction + mode_excitation(otter.gap_modes, otter.omega) == pytest.approx(
        otter.diffraction)
    before, after = narrow_peaks(otter), narrow_peaks(smooth)
    assert len(before) == 17 and max(p.ratio for p in before) > 100.0
    assert len(after) <= 1 and all(p.ratio < 5.0 for p in after), after
    assert dof_blocks(otter) == [[0, 4], [1, 3], [2], [5]]


def test_moving_and_scaling_carry_the_modes(otter, memory):
    there = moved(otter, np.array([0.3, 0.0, -0.1]))
    back = moved(there, otter.center_of_mass)
    for m, b in zip(otter.gap_modes, back.gap_modes, strict=True):
        assert b.residue == pytest.approx(m.residue, abs=1e-9 * np.abs(m.residue).max())
        assert b.excitation == pytest.approx(m.excitation)
    big = froude_scaled(otter, 4.0)
    assert [m.omega0 for m in big.gap_modes] == pytest.approx(
        [m.omega0 / 2.0 for m in otter.gap_modes])
    k = mode_kernel(big.gap_modes, big.omega)[:, 1, 1].real
    assert k == pytest.approx(mode_kernel(otter.gap_modes, otter.omega)[:, 1, 1].real
                              * 4.0**2.5)


def _rewritten(tmp_path: Path, **changes) -> Path:
    with np.load(OTTER, allow_pickle=False) as d:
        arrays = {k: d[k] for k in d.files}
    for name, value in changes.items():
        if value is None:
            del arrays[name]
        else:
            arrays[name] = value
    out = tmp_path / "otter.npz"
    np.savez(out, **arrays)
    return out


@pytest.mark.parametrize(("change", "match"), [
    ({"gap_mode_zeta": None}, r"gap mode arrays \['gap_mode_zeta'\] are missing"),
    ({"gap_mode_zeta": np.full(15, 1.5)}, r"gap_mode_zeta .*: each in \(0, 1\)"),
    ({"gap_mode_omega": -np.ones(15)}, r"gap_mode_omega .*: each in \(0, 200\]"),
    ({"gap_mode_excitation": np.zeros((15, 4, 6), complex)},
     r"gap_mode_excitation has shape \(15, 4, 6\): D = 4, but 5 elsewhere"),
    ({"gap_mode_residue": np.full((15, 6, 6), np.nan)}, "gap_mode_residue has non-finite"),
    ({"gap_mode_omega": np.ones(15, complex)}, "must be real"),
])
def test_malformed_gap_modes_are_refused_by_name(tmp_path, change, match):
    with pytest.raises(HydroFileError, match=match):
        load_coefficients(_rewritten(tmp_path, **change))


def test_a_file_without_modes_loads_as_before(tmp_path):
    names = ["gap_mode_omega", "gap_mode_zeta", "gap_mode_residue", "gap_mode_excitation"]
    plain = load_coefficients(_rewritten(tmp_path, **dict.fromkeys(names)))
    assert plain.gap_modes == ()
