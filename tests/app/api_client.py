# SPDX-License-Identifier: LGPL-3.0-or-later
"""A small client of the breastsim serve API for the tests (python3 stdlib only)."""
import http.client
import json
import time


class Api:
    def __init__(self, port, timeout=30):
        self.port, self.timeout = port, timeout

    def raw(self, method, path, body=None, headers=None):
        """Send `path` exactly as given (no normalisation); (status, headers, body bytes)."""
        c = http.client.HTTPConnection("127.0.0.1", self.port, timeout=self.timeout)
        try:
            h = dict(headers or {})
            c.putrequest(method, path, skip_host="Host" in h, skip_accept_encoding=True)
            data = body.encode() if isinstance(body, str) else body
            if data is not None:
                h.setdefault("Content-Length", str(len(data)))
            for k, v in h.items():
                c.putheader(k, v)
            c.endheaders(data)
            r = c.getresponse()
            return r.status, dict(r.getheaders()), r.read()
        finally:
            c.close()

    def json(self, method, path, doc=None):
        """(status, parsed JSON answer) of a request with a JSON body."""
        body = None if doc is None else json.dumps(doc)
        h = {"Content-Type": "application/json"} if body is not None else {}
        status, _, data = self.raw(method, path, body, h)
        return status, json.loads(data)

    def wait(self, job_id, states, seconds):
        """The job's record once its state is one of `states` (AssertionError after `seconds`)."""
        end = time.time() + seconds
        while time.time() < end:
            status, r = self.json("GET", f"/api/jobs/{job_id}")
            assert status == 200, (status, r)
            if r["state"] in states:
                return r
            time.sleep(0.3)
        raise AssertionError(f"job {job_id} not in {states} after {seconds} s: {r}")
