!> The state of a dynamic run at one time t: what a time step reads at t and
!> writes at t + dt. Nodal vectors are in band (equation) order, two per node
!> (r, z); stresses and strains at the Gauss points, (4, gauss_count, nelem).
module visco2d_dynamic_state
  use visco2d_kinds, only: dp
  use visco2d_viscoelastic, only: viscoelastic_state_t
  use visco2d_finite_viscoelastic, only: viscoelastic_point_t
  implicit none
  private

  public :: dynamic_state_t

  !> u, v, a of eqs. [40]-[42], the stresses and strains of eqs. [13], [14],
  !> the Prony histories of eqs. [23], [24], and the forces at t.
  type :: dynamic_state_t
    real(dp) :: t = 0.0_dp                          !< time, s
    real(dp), allocatable :: u(:), v(:), a(:)       !< displacement U, velocity U', acceleration U''
    real(dp), allocatable :: stress(:, :, :)        !< sigma at the Gauss points
    real(dp), allocatable :: strain(:, :, :)        !< total strain at the Gauss points
    type(viscoelastic_state_t) :: history           !< the Prony histories C_m (only with memory)
    real(dp), allocatable :: load(:)                !< external load R(t)
    real(dp), allocatable :: internal(:)            !< internal force F(sigma_t) = sum B^T sigma |J| r
    real(dp), allocatable :: reaction(:)            !< support reactions M a + F - R - G (0 off the supports)
    real(dp), allocatable :: target(:)              !< the prescribed (FIX) displacements at t
    !> With a PLASTIC material only (visco2d_plastic_step): the equivalent
    !> plastic strain ebar (gauss_count, nelem) and the plastic strain
    !> (4, gauss_count, nelem, engineering shear), both 0 off the plastic materials.
    real(dp), allocatable :: ebar(:, :), plastic_strain(:, :, :)
    !> With KINEMATICS LARGE only: the stored energy W of the hyperelastic
    !> bodies at U (J per radian in axisymmetry); strain is then the
    !> logarithmic strain and stress the Cauchy stress.
    real(dp) :: strain_energy = 0.0_dp
    !> With KINEMATICS LARGE and a material that relaxes: the Gauss points'
    !> histories of Simo's finite-strain viscoelasticity (gauss, nelem).
    type(viscoelastic_point_t), allocatable :: finite_history(:, :)
  end type dynamic_state_t
end module visco2d_dynamic_state
