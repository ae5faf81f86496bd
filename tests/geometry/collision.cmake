# Collision layer tests: one file per source (included from tests/geometry/CMakeLists.txt).
foreach(test FclAdapterTest MeshLoaderTest BroadPhaseTest PrimitiveContactsTest BoxContactsTest
             ManifoldBuilderTest HullContactsTest NarrowPhaseTest ContactCacheTest CollisionPipelineTest
             RayCastTest SceneQueryTest)
  coulomb_add_test(${test}.cpp LINKS coulomb::meshes LABELS unit)
endforeach()
if(TARGET coulomb_samples)  # its hulls come from samples/bench/ShapeFixtures
  coulomb_add_test(FeatureContactsTest.cpp LINKS coulomb_samples LABELS unit)
endif()
