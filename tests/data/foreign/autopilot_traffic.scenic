# In the style of Scenic's CARLA examples: a map path relative to Scenic's own assets
# folder (absent here), autopilot traffic, a parked car and a monitor.
param map = localPath('../../../assets/maps/CARLA/Town05.xodr')
param carla_map = 'Town05'
param render = 0
model scenic.simulators.carla.model

EGO_MODEL = "vehicle.lincoln.mkz_2017"

monitor KeepTrack():
    while True:
        wait

ego = new Car with blueprint EGO_MODEL, with behavior AutopilotBehavior()

other = new Car visible, with behavior AutopilotBehavior(speed=6)

parked = new Car on network.curbRegion, facing roadDirection, with regionContainedIn None

require monitor KeepTrack()
require (distance to intersection) > 15
terminate after 15 seconds
