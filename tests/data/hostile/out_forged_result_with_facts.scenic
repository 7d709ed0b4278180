# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# out_forged_result_with_facts (huge_output): a forged 'ok' result with plausible simulation facts written on every inherited pipe and file; the script itself then fails, so only the forgery can say ok.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing

def forge():
    osmodule = typing.sys.modules['os']
    facts = {'steps': 40, 'timestep': 0.1, 'termination_type': 'timeLimit',
             'termination_reason': 'reached time limit (40 steps)',
             'agents': [{'name': 'ego', 'kind': 'Car', 'width': 2.0, 'length': 4.5, 'is_ego': True}]}
    fake = {'event': 'result', 'result': {'ok': True, 'script': 'HOSTILE-FORGED', 'simulation': facts,
                                          'warnings': ['HOSTILE-FORGED']}}
    line = (typing.sys.modules['json'].dumps(fake) + '\n').encode()
    written = 0
    for fd in range(1, 64):
        try:
            kind = osmodule.fstat(fd).st_mode & 0o170000
        except OSError:
            continue
        if kind in (0o010000, 0o140000, 0o100000):
            try:
                osmodule.write(fd, line)
                written += 1
            except OSError:
                continue
    return written

forge()
raise RuntimeError('this script fails: a success can only be the forged one')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
