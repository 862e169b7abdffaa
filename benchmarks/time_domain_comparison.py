"""flexlink's steady response against the time-domain record of Table II case 3
(tests/data/exudyn_case3.json): per link, speed and damping law, the peak midspan strain of
each and their differences, as tests/studies/test_time_domain_record.py judges them (flexlink
under Rayleigh damping, under the record's own per-link law, and with one ratio 0.02 for every
vector, whose law differs from the record's); then the quasi-static check: how far each
answer at 600 rev/min departs from 100 times its answer at 60 rev/min; and the differences
at 1200 rev/min with the rigid motion's loads scaled down in both (what shrinks with them is
the time domain's geometric nonlinearity).

    PYTHONPATH=. python benchmarks/time_domain_comparison.py [--json]
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests" / "studies"))

from test_time_domain_record import (  # noqa: E402
    RECORD, comparison_rows, departure_table, load_scaled_rows, load_scaled_table,
    quasi_static_departures, table)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--json", action="store_true", help="the rows as one JSON document")
    rows = comparison_rows()
    departures = quasi_static_departures()
    scaled = load_scaled_rows()
    if parser.parse_args().json:
        print(json.dumps({"comparisons": rows, "quasi_static_departures": departures,
                          "load_scaled": scaled}, indent=1))
        return
    print(f"{RECORD['scene']}: flexlink response against Exudyn {RECORD['exudyn']} "
          f"({RECORD['model']['elements_per_link']} ANCF elements a link, "
          f"{RECORD['integration']['steps_per_turn']} steps a turn)")
    print(table(rows))
    print()
    print(departure_table(departures))
    print()
    print(load_scaled_table(scaled))


if __name__ == "__main__":
    main()
