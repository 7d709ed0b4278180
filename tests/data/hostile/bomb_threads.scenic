# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# bomb_threads (bomb): a (bounded) thread bomb: 2000 threads with small stacks, so the memory limit does not stop it.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing

behavior Payload():
    threads = typing.sys.modules['threading']
    threads.stack_size(65536)
    release = threads.Event()
    started = []
    for index in range(2000):
        worker = threads.Thread(target=release.wait, args=(15,), daemon=True)
        worker.start()
        started.append(worker)
    release.set()
    for worker in started:
        worker.join()
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
