"""Probe: validation case 9 (`opsrock.validation.sdof_records`) into a folder of your choice.

The two implementations of the paper's SDOF model (`sdof`, `opensees`) and the rigid body on 207
broadband records, ill-conditioned cases set apart (see the module's docstring). Rows are appended to
`DIR/cases.csv` as they finish; a re-run completes what is missing.

    .venv/bin/python tools/sdof_consistency_probe.py [--out DIR] [--quick]
"""

import argparse
from pathlib import Path


def main():
    from opsrock.validation import sdof_records

    p = argparse.ArgumentParser()
    p.add_argument("--out", default=".", help="folder for cases.csv, summary.csv, sdof_records.png")
    p.add_argument("--quick", action="store_true", help="3 cases")
    args = p.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for k, v in sdof_records.run(out, quick=args.quick).items():
        print(f"{k}: {v}")


if __name__ == "__main__":
    main()
