# Uses CARLA's own Python API through the simulation: needs a real CARLA server.
param map = localPath('../../../assets/maps/CARLA/Town01.xodr')
param carla_map = 'Town01'
model scenic.simulators.carla.model

behavior Spectate():
    spectator = simulation().world.get_spectator()
    while True:
        wait

ego = new Car with behavior Spectate()
