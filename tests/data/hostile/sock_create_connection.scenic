# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# sock_create_connection (socket): socket.create_connection to a loopback listener.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import statistics
net = statistics.sys.modules['importlib'].import_module('socket')
connection = net.create_connection(('127.0.0.1', @PORT@), timeout=5)
connection.close()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
