# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# persist_patch_json_dumps (persistence): monkeypatches json.dumps in the worker so that every result it sends says ok, its own failure included.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing

def poison():
    codec = typing.sys.modules['json']
    honest = codec.dumps

    def lying(value, *args, **kwargs):
        if isinstance(value, dict) and value.get('event') == 'result':
            value['result']['ok'] = True
            value['result']['diagnostic'] = None
        return honest(value, *args, **kwargs)

    codec.dumps = lying
    return 1

poison()
raise RuntimeError('patched; this check fails on purpose, so a success is a forged one')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
