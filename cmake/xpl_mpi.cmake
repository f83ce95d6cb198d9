# XPL_MPI=ON (issue 37, docs/dev/mpi.md): OpenMPI, METIS and the OpenMPI build of HDF5, each
# selected explicitly. Debian installs the serial and the MPI HDF5 side by side; FindHDF5
# would take whichever wrapper or hdf5.pc it meets first, so the MPI wrapper h5pcc is named.

find_package(MPI REQUIRED COMPONENTS CXX)

find_path(XPL_METIS_INCLUDE_DIR metis.h)
find_library(XPL_METIS_LIBRARY metis)
if(NOT XPL_METIS_INCLUDE_DIR OR NOT XPL_METIS_LIBRARY)
  message(FATAL_ERROR "XPL_MPI=ON needs METIS (Debian: apt-get install libmetis-dev)")
endif()

find_program(XPL_HDF5_MPI_WRAPPER NAMES h5pcc.openmpi h5pcc
             DOC "HDF5 compiler wrapper of the MPI build, to find the parallel HDF5")
if(NOT XPL_HDF5_MPI_WRAPPER)
  message(FATAL_ERROR "XPL_MPI=ON needs the MPI build of HDF5 (Debian: apt-get install "
                      "libhdf5-openmpi-dev)")
endif()
set(HDF5_PREFER_PARALLEL TRUE)
set(HDF5_C_COMPILER_EXECUTABLE ${XPL_HDF5_MPI_WRAPPER} CACHE FILEPATH
    "HDF5 C wrapper compiler (XPL_MPI=ON: the MPI build's)" FORCE)
find_package(HDF5 REQUIRED COMPONENTS C)
if(NOT HDF5_IS_PARALLEL)
  message(FATAL_ERROR "XPL_MPI=ON: the HDF5 found (${HDF5_C_LIBRARIES}) is not the MPI build")
endif()
# The parallel hdf5.h includes mpi.h.
target_link_libraries(hdf5::hdf5 INTERFACE MPI::MPI_CXX)
message(STATUS "XPL_MPI: MPI ${MPI_CXX_VERSION}, METIS ${XPL_METIS_LIBRARY}, HDF5 "
               "${HDF5_C_LIBRARIES} (parallel)")
