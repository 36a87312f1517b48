# Sourced after unpacking the bundle (bench/portable/pack.sh): its programs first on PATH, its libraries
# first for the loader, Open MPI and PMIx relocated into it; as root (a lent machine), mpirun is allowed.
DEM2D_BUNDLE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export DEM2D_BUNDLE
export PATH="$DEM2D_BUNDLE/bin:$DEM2D_BUNDLE/usr/bin:$PATH"
export LD_LIBRARY_PATH="$DEM2D_BUNDLE/lib:$DEM2D_BUNDLE/usr/lib/x86_64-linux-gnu/openmpi/lib:$DEM2D_BUNDLE/usr/lib/x86_64-linux-gnu/pmix2/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export OPAL_PREFIX="$DEM2D_BUNDLE/usr"
export OPAL_SYSCONFDIR="$DEM2D_BUNDLE/etc/openmpi"
export PMIX_INSTALL_PREFIX="$DEM2D_BUNDLE/usr/lib/x86_64-linux-gnu/pmix2"
export PMIX_MCA_mca_base_component_path="$DEM2D_BUNDLE/usr/lib/x86_64-linux-gnu/pmix2/lib/pmix"
export OMPI_MCA_mca_base_component_path="$DEM2D_BUNDLE/usr/lib/x86_64-linux-gnu/openmpi/lib/openmpi3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_pml=ob1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_plm_rsh_agent=false   # one node: no ssh
