# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# sock_urllib_urlopen (socket): urllib.request.urlopen to a loopback listener at simulation time.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing

behavior Payload():
    web = typing.sys.modules['importlib'].import_module('urllib.request')
    web.urlopen('http://127.0.0.1:@PORT@/', timeout=5).read()
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
