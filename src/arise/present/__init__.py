"""What a validated run looks like to people and to other simulators: the animated replay
(GIF, HTML) and the ASAM OpenSCENARIO export, both drawn from the validator's trace.

Scripts run only in the confined worker (`arise.validate.check`); this package reads
traces, maps we know, and run folders.
"""
