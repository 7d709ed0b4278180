"""Offline CARLA world model for arise.

Mirrors the names of Scenic's ``scenic.simulators.carla.model`` (classes, blueprints,
global parameters, actions, behaviors, traffic-light helpers) so CARLA scripts compile
and run unchanged, but simulates with arise's kinematic simulator and never connects to
a CARLA server.
"""

import pathlib

from scenic.domains.driving.model import *

import scenic.simulators.carla.blueprints as blueprints
from scenic.simulators.utils.colors import Color

from arise.validate.worldmodel.actions import *
from arise.validate.worldmodel.actions import _CarlaVehicle, _CarlaPedestrian, _check_color
from arise.validate.worldmodel.behaviors import *
from arise.validate.worldmodel.simulator import OfflineCarlaSimulator

map_town = pathlib.Path(globalParameters.map).stem
param carla_map = map_town
param address = '127.0.0.1'
param port = 2000
param timeout = 10
param render = 1
if globalParameters.render not in [0, 1]:
    raise ValueError('render param must be either 0 or 1')
param record = ''
param timestep = 0.1
param weather = Uniform('ClearNoon', 'CloudyNoon', 'WetNoon', 'WetCloudyNoon',
                        'SoftRainNoon', 'MidRainyNoon', 'HardRainNoon', 'ClearSunset',
                        'CloudySunset', 'WetSunset', 'WetCloudySunset', 'SoftRainSunset',
                        'MidRainSunset', 'HardRainSunset')
param snapToGroundDefault = is2DMode()

simulator OfflineCarlaSimulator(network, timestep=float(globalParameters.timestep))

def CarlaSimulator(*args, **kwargs):
    """Scripts that name CarlaSimulator get the offline simulator."""
    return OfflineCarlaSimulator(network, timestep=float(kwargs.get('timestep', 0.1)))

class CarlaActor(DrivingObject):
    carlaActor: None
    blueprint: None
    defaultWidth: 1
    defaultLength: 1
    defaultHeight: 1
    width: blueprints.width(self.blueprint, self.defaultWidth)
    length: blueprints.length(self.blueprint, self.defaultLength)
    height: blueprints.height(self.blueprint, self.defaultHeight)
    rolename: None
    physics: True
    snapToGround: globalParameters.snapToGroundDefault
    arise_steers: False
    arise_autopilot: None
    arise_turns: None
    arise_angular_override: None

    def setPosition(self, pos, elevation):
        self.position = pos

    def setVelocity(self, vel):
        self.velocity = vel

class Vehicle(CarlaActor, Vehicle, Steers, _CarlaVehicle):
    throttle: 0
    steer: 0
    brake: 0
    hand_brake: 0
    reverse: 0
    arise_steers: True

    def setThrottle(self, throttle):
        self.throttle = throttle

    def setSteering(self, steering):
        self.steer = steering

    def setBraking(self, braking):
        self.brake = braking

    def setHandbrake(self, handbrake):
        self.hand_brake = handbrake

    def setReverse(self, reverse):
        self.reverse = reverse

class Car(Vehicle):
    blueprint: Uniform(*blueprints.blueprintsInCategory("car"))
    defaultWidth: 2
    defaultLength: 4.5
    defaultHeight: 1.5

    @property
    def isCar(self):
        return True

class NPCCar(Car):
    pass

class Bicycle(Vehicle):
    blueprint: Uniform(*blueprints.blueprintsInCategory("bicycle"))
    defaultWidth: 1
    defaultLength: 2
    defaultHeight: 1.5

class Motorcycle(Vehicle):
    blueprint: Uniform(*blueprints.blueprintsInCategory("motorcycle"))
    defaultWidth: 1
    defaultLength: 2
    defaultHeight: 1.5

class Truck(Vehicle):
    blueprint: Uniform(*blueprints.blueprintsInCategory("truck"))
    defaultWidth: 2.5
    defaultLength: 7.5
    defaultHeight: 3

class Van(Vehicle):
    blueprint: Uniform(*blueprints.blueprintsInCategory("van"))
    defaultWidth: 2
    defaultLength: 5
    defaultHeight: 2

class Bus(Vehicle):
    blueprint: Uniform(*blueprints.blueprintsInCategory("bus"))
    defaultWidth: 4
    defaultLength: 10
    defaultHeight: 4

class Pedestrian(CarlaActor, Pedestrian, Walks, _CarlaPedestrian):
    blueprint: Uniform(*blueprints.blueprintsInCategory("walker"))
    defaultWidth: 0.5
    defaultLength: 0.5
    defaultHeight: 1.5
    carlaController: None

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.arise_walk = [None, None]

    def setWalkingDirection(self, heading):
        self.arise_walk[0] = heading

    def setWalkingSpeed(self, speed):
        self.arise_walk[1] = speed

class Prop(CarlaActor):
    regionContainedIn: road
    position: new Point on road
    parentOrientation: Range(0, 360) deg
    defaultWidth: 0.5
    defaultLength: 0.5
    defaultHeight: 0.5
    physics: False

class Trash(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("trash"))

class Cone(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("cone"))

class Debris(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("debris"))

class VendingMachine(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("vendingMachine"))

class Chair(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("chair"))

class BusStop(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("busStop"))

class Advertisement(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("advertisement"))

class Garbage(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("garbage"))

class Container(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("container"))

class Table(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("table"))

class Barrier(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("barrier"))

class PlantPot(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("plantpot"))

class Mailbox(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("mailbox"))

class Gnome(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("gnome"))

class CreasedBox(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("creasedbox"))

class Case(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("case"))

class Box(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("box"))

class Bench(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("bench"))

class Barrel(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("barrel"))

class ATM(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("atm"))

class Kiosk(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("kiosk"))

class IronPlate(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("ironplate"))

class TrafficWarning(Prop):
    blueprint: Uniform(*blueprints.blueprintsInCategory("trafficwarning"))

## Traffic lights: offline their state is kept by the simulator and recorded.

def freezeTrafficLights():
    simulation().arise_events.append({'step': simulation().currentTime, 'agent': 'world',
                                      'kind': 'freeze_traffic_lights'})

def unfreezeTrafficLights():
    simulation().arise_events.append({'step': simulation().currentTime, 'agent': 'world',
                                      'kind': 'unfreeze_traffic_lights'})

def _colorOf(color):
    return _check_color(color)

def setTrafficLightStatus(signal, color):
    if not signal.isTrafficLight:
        raise RuntimeError('The provided signal is not a traffic light')
    simulation().arise_set_signal(signal, _colorOf(color))

def setAllIntersectionTrafficLightsStatus(intersection, color):
    for signal in intersection.signals:
        if signal.isTrafficLight:
            setTrafficLightStatus(signal, color)

def getTrafficLightStatus(signal):
    if not signal.isTrafficLight:
        raise RuntimeError('The provided signal is not a traffic light')
    return simulation().arise_lights.get(str(signal.openDriveID), 'Green').capitalize()

def withinDistanceToRedYellowTrafficLight(vehicle, thresholdDistance):
    return simulation().arise_light_of(vehicle) in ('red', 'yellow')

def withinDistanceToTrafficLight(vehicle, thresholdDistance):
    return simulation().arise_light_of(vehicle) is not None

def getClosestTrafficLightStatus(vehicle, distance=100):
    color = simulation().arise_light_of(vehicle)
    return 'None' if color is None else color.capitalize()

def setClosestTrafficLightStatus(vehicle, color, distance=100):
    simulation().arise_set_closest_light(vehicle, _colorOf(color), distance)
