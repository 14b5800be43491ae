"""``rsm-lrg calibrate``: fit the surrogate's unknown parameters to measured runs."""

from __future__ import annotations

import argparse

from .errors import about_file
from .options import add_force, add_json, add_reader_options

NAME = "calibrate"
HELP = "fit the surrogate's unknown parameters to measured runs"
DESCRIPTION = (
    "Fit at most three parameters the paper does not give (model v5, the default: one heat balance in "
    "watts, the friction power at the ball contacts and the drive's viscous heat entering the working "
    "stage through one network of the rig's bodies; calibrated: the viscous friction of the block, "
    "that of the drive, and the conductance of the ball contacts; --model v5-nodrive: no drive heat; "
    "--model v4: the earlier calibration, a share of Eq. 8's calories plus a drive heat; v4-coulomb, "
    "v3, v3-overconstraint, v2: earlier models; --select M1,M2: the candidate of smallest AICc, the "
    "choice repeated inside every leave-one-out fold; --model v6 / v6-alone: both carriages on one rail "
    "and base (Section 4.1), the other stage running or at rest, no drive heat, the ball contacts within "
    "3x of their contact-mechanics estimate; the shipped file selects between them) "
    "by bounded least squares to the measured response of noise-free virtual runs; report R2, "
    "RMSE, standard errors and leave-one-out cross-validation next to the paper's quadratic's "
    "PRESS R2 (0.818), and write them with the data's "
    "name and SHA-256 to a TOML file that `rsm-lrg simulate --calibration PATH` reads "
    "(data/calibration.toml is the shipped default)."
)


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("data", metavar="DATA.csv", help="measured runs: the design columns and the response")
    add_reader_options(p)
    p.add_argument("--response", required=True, metavar="COL", help="the measured column (e.g. tcr_c_per_min)")
    p.add_argument("--model", default="v5", choices=("v4", "v5", "v5-nodrive", "v6", "v6-alone", "v4-coulomb", "v3",
                                                     "v3-overconstraint", "v2"),
                   help="calibration model: the physics it fixes and its default parameters (default v5: one "
                        "heat balance in watts; v4: a share of Eq. 8's calories plus a drive heat; v2 reproduces "
                        "the earliest calibration)")
    p.add_argument("--parameter", action="append", default=None, metavar="NAME",
                   help="a parameter to calibrate (repeatable, at most 3; default: the model's -- v5: "
                        "viscous_friction_n_s_m, drive_viscous_n_s_m, ball_contact_conductance_w_k; v4: "
                        "heat_partition, viscous_friction_n_s_m, drive_viscous_n_s_m; v4-coulomb: "
                        "drive_friction_n instead of drive_viscous_n_s_m; v3: "
                        "heat_partition, viscous_friction_n_s_m, drive_heat_w; v3-overconstraint: "
                        "overconstraint_misfit_m instead of drive_heat_w; v2: heat_partition, "
                        "viscous_friction_n_s_m, hinge_damping_ratio; also hinge_length_m, hinge_width_m, "
                        "frame_mass_fraction)")
    p.add_argument("--select", default=None, metavar="M1,M2,...",
                   help="candidate models (comma-separated, e.g. v5,v5-nodrive): each is calibrated and the one "
                        "of smallest AICc kept; leave-one-out repeats the choice inside every fold (--model and "
                        "--parameter are then not used)")
    from .options import number

    p.add_argument("--duration-min", type=number(1), default=50.0, metavar="M",
                   help="test duration of the measured runs [min] (default 50)")
    p.add_argument("--no-loo", action="store_true", help="skip leave-one-out cross-validation")
    p.add_argument("--no-progress", dest="progress", action="store_false", default=True,
                   help="no progress bar on stderr (default: one step per least-squares fit)")
    p.add_argument("-o", "--output", default=None, metavar="PATH.toml", help="write the calibration TOML here")
    add_json(p)
    add_force(p)


def _safe_name(name: str) -> str:
    """A file name as text that can be written to UTF-8 TOML: bytes that are not UTF-8
    (kept by Python as lone surrogates) become U+FFFD."""
    return name.encode("utf-8", "surrogateescape").decode("utf-8", "replace")


def run(args) -> int:
    import shlex
    import sys
    from pathlib import Path

    from ..io import InputError, check_output, dump_json, write_output
    from ..surrogate.calibrate import calibrate, calibration_toml, file_sha256
    from ..surrogate.runs import check_duration
    from .paths import read_input

    if args.output:
        check_output(args.output, force=args.force, option="-o/--output")
    try:
        duration = check_duration(args.duration_min, "--duration-min")
    except ValueError as exc:
        raise InputError(str(exc)) from None
    select = None
    if args.select is not None:
        from ..surrogate.calibrate import MODELS

        select = [m.strip() for m in str(args.select).split(",")]
        bad = [m for m in select if m not in MODELS]
        if bad or not select or len(set(select)) != len(select):
            what = f"{bad[0]!r} is not a calibration model" if bad else "give different models"
            raise InputError(f"--select: {what} (choose among {', '.join(MODELS)})")
        if args.parameter:
            raise InputError("--select: the candidates calibrate their own parameters; drop --parameter")
    data = read_input(args)
    with about_file(args.data):
        cal = calibrate(data, args.response, parameters=args.parameter, duration_min=duration,
                        loo=not args.no_loo, source=_safe_name(Path(args.data).name),
                        data_sha256=file_sha256(args.data), progress=args.progress, model=args.model,
                        select=select)
    print(cal.summary())
    argv = [_safe_name(a) for a in sys.argv[2:]]
    cmd = "rsm-lrg calibrate " + " ".join(shlex.quote(a) for a in argv) if argv else ""
    if args.output:
        write_output(args.output, calibration_toml(cal, cmd), force=args.force)
        print(f"calibrate: written to {args.output}", file=sys.stderr)
    if args.json:
        dump_json(cal.to_dict(), args.json, force=args.force)
    return 0
