# Type stubs of refract.fraunhofer: Fraunhofer and helium lines, nm.
B: float
C: float
D: float
d: float
F: float
G: float
