// The "host" build of the device back end: device_backend.cu compiled by g++ against CCCL with Thrust's
// OpenMP device system, so every machine runs (and tests) the device code on its CPU cores.
#define SPH_DEVICE_NS host_device
#define SPH_DEVICE_FACTORY make_host_backend
#define SPH_DEVICE_NAME "host"
#define SPH_DEVICE_PREPARE() ((void)0)
#include "device_backend.cu"
