# Collision layer tests: one file per source (included from tests/geometry/CMakeLists.txt).
foreach(test FclAdapterTest MeshLoaderTest BroadPhaseTest PrimitiveContactsTest BoxContactsTest
             ManifoldBuilderTest HullContactsTest NarrowPhaseTest ContactCacheTest CollisionPipelineTest
             RayCastTest SceneQueryTest FeatureContactsTest)
  coulomb_add_test(${test}.cpp LINKS coulomb::meshes LABELS unit)
endforeach()
