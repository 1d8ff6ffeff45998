# SPDX-License-Identifier: LGPL-3.0-or-later
"""Load test of `breastsim serve`: 200 concurrent requests, 50 of them malformed,
all answered with the expected status within a time bound, the server still up.

Usage: load.py PORT
"""
import sys
import threading
import time

from api_client import Api

CONCURRENT, MALFORMED, BOUND_S = 200, 50, 60

JSON = {"Content-Type": "application/json"}
GOOD = [  # (method, path, body, headers, expected status)
    ("GET", "/api/keys", None, {}, 200),
    ("POST", "/api/validate", '{"incision.a_deg": 40}', JSON, 200),
    ("POST", "/api/incision/check", '{"incision.h": 0.02}', JSON, 200),
    ("GET", "/api/jobs", None, {}, 200),
    ("GET", "/", None, {}, 200),
]
BAD = [
    ("POST", "/api/validate", '{"incision.a_deg": ', JSON, 400),
    ("POST", "/api/validate", '{"no.key": 1}', JSON, 400),
    ("POST", "/api/incision/check", '{"incision.s": 9}', JSON, 400),
    ("POST", "/api/incision/check", '{"incision.a_deg": "x"}', JSON, 400),
    ("POST", "/api/jobs", '{"kind": "surgery", "overrides": []}', JSON, 400),
    ("POST", "/api/validate", "[" * 100000, JSON, 400),
    ("POST", "/api/validate", '{"case.name": "' + "x" * (2 << 20) + '"}', JSON, 413),
    ("GET", "/api/jobs/../../etc/passwd", None, {}, 404),
    ("GET", "/api/jobs/%2e%2e/x/files/passwd", None, {}, 404),
    ("POST", "/api/validate", "{}", {"Content-Type": "text/plain"}, 415),
    ("GET", "/api/keys", None, {"Host": "attacker.example"}, 403),
]


def main(port):
    api = Api(port, timeout=BOUND_S)
    plan = [BAD[i % len(BAD)] for i in range(MALFORMED)]
    plan += [GOOD[i % len(GOOD)] for i in range(CONCURRENT - MALFORMED)]
    results = [None] * len(plan)
    start = threading.Barrier(len(plan))

    def send(i):
        method, path, body, headers, _ = plan[i]
        start.wait()
        try:
            results[i] = api.raw(method, path, body, headers)[0]
        except Exception as e:  # a refused or reset connection counts as unanswered
            results[i] = repr(e)

    threads = [threading.Thread(target=send, args=(i,)) for i in range(len(plan))]
    t0 = time.time()
    for t in threads:
        t.start()
    for t in threads:
        t.join(BOUND_S)
    elapsed = time.time() - t0
    wrong = [(plan[i][1][:40], plan[i][4], r) for i, r in enumerate(results) if r != plan[i][4]]
    print(f"{len(plan)} concurrent requests ({MALFORMED} malformed) answered in {elapsed:.2f} s; "
          f"{len(wrong)} unexpected")
    for w in wrong[:10]:
        print("  unexpected:", w)
    status, _ = api.json("GET", "/api/keys")
    print("server still up:", status == 200)
    return 0 if not wrong and status == 200 and elapsed < BOUND_S else 1


if __name__ == "__main__":
    sys.exit(main(int(sys.argv[1])))
