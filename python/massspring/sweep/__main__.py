"""python3 -m massspring.sweep SPEC.json --out results.h5 [options]: runs a sweep (docs/sweeps.md).

Exit status: 0 when every run of the spec is in the file (each "ok", "diverged", "skipped" or
"failed": see its message), 1 for an invalid spec, option or output file (nothing is run), 130 when
interrupted (the runs committed so far stay; the same command continues)."""

import argparse
import sys


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python3 -m massspring.sweep",
        description="Run a grid of massspring runs on a Dask cluster; one HDF5 file of results. "
                    "A rerun skips the runs the file holds.")
    parser.add_argument("spec", help="the sweep's JSON spec (docs/sweeps.md)")
    parser.add_argument("--out", help="the HDF5 results file (created or extended); needed "
                                      "unless --check")
    parser.add_argument("--scheduler", default=None,
                        help="an existing Dask scheduler, tcp://HOST:8786 (default: a local "
                             "cluster of --workers processes)")
    parser.add_argument("--workers", type=int, default=None,
                        help="the local cluster's worker processes, one thread each (default: the "
                             "machine's cores)")
    parser.add_argument("--redo-failed", action="store_true",
                        help="run again the runs recorded as failed, diverged or skipped")
    parser.add_argument("--check", action="store_true",
                        help="check the spec and list its runs; run nothing")
    parser.add_argument("--quiet", action="store_true", help="no progress bar or summary")
    parser.add_argument("--verbose", action="store_true",
                        help="also show Dask's own log lines (its warnings and errors, e.g. a "
                             "worker restarted) and the local workers' stderr")
    args = parser.parse_args(argv)
    if not args.out and not args.check:
        parser.error("--out FILE is needed (the HDF5 results file)")
    if args.workers is not None and args.workers < 1:
        parser.error(f"--workers must be >= 1, got {args.workers}")
    if args.workers is not None and args.scheduler:
        parser.error("--workers applies to the local cluster, not to --scheduler")

    from .spec import SpecError  # noqa: PLC0415

    if not args.check:
        try:
            import dask.distributed  # noqa: F401,PLC0415
            import h5py  # noqa: F401,PLC0415
        except ImportError as e:
            print(f"massspring.sweep: needs Dask and h5py ({e}; Debian: python3-dask "
                  "python3-distributed python3-h5py, which scripts/setup.sh installs)",
                  file=sys.stderr)
            return 1
    try:
        if args.check:
            from .driver import check, command_line  # noqa: PLC0415

            runs, _ = check(args.spec)
            for run in runs:
                cli = command_line(run)
                print(f"{run.index}\t{run.id}\t{run.origin}"
                      + (f"\tmassspring-simulate {' '.join(cli)}" if cli else ""))
            print(f"{args.spec}: {len(runs)} runs, every one valid", file=sys.stderr)
            return 0
        from .driver import sweep  # noqa: PLC0415

        sweep(args.spec, args.out, scheduler=args.scheduler, workers=args.workers,
              redo_failed=args.redo_failed, progress=not args.quiet, verbose=args.verbose)
    except SpecError as e:
        print(f"massspring.sweep: {e}", file=sys.stderr)
        return 1
    except (OSError, ValueError) as e:  # the results file, or the scheduler's address
        print(f"massspring.sweep: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"massspring.sweep: interrupted; the runs committed so far are in {args.out} (the "
              "same command continues)", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":
    sys.exit(main())
