"""`arise serve`: the generator and the validator in a browser, on this machine.

One page (static files in `static/`, no build step, no CDN), a JSON API and an SSE stream
of each job's progress events. Jobs wait in one queue per model (`lanes`), runs live in a
folder on disk (`store`), and every script runs only in the confined validator.
"""
