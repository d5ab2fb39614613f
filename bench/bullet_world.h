// A Bullet dynamics world with its default parts (collision configuration,
// dispatcher, dynamic-tree broad phase, sequential-impulse solver), as both
// Bullet peers set it up.
#pragma once

#include <btBulletDynamicsCommon.h>

namespace asgard::bench {

struct BulletWorld {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
};

}  // namespace asgard::bench
