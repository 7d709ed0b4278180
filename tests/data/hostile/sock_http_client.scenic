# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# sock_http_client (socket): http.client.HTTPConnection to a loopback listener from a monitor.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import enum

monitor Payload():
    client = enum.sys.modules['importlib'].import_module('http.client')
    connection = client.HTTPConnection('127.0.0.1', @PORT@, timeout=5)
    connection.request('GET', '/hostile')
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
