!> Hyperelastic flesh for finite deformation (KINEMATICS LARGE): the
!> compressible neo-Hookean and Mooney-Rivlin laws in the form ABAQUS and
!> CalculiX users give them,
!>
!>   W = C10 (I1bar - 3) + C01 (I2bar - 3) + (J - 1)^2 / D1,
!>
!> I1bar, I2bar the invariants of the isochoric left Cauchy-Green tensor
!> bbar = J^(-2/3) F F^T, J = det F. The small-strain limit is linear
!> elasticity with G = 2 (C10 + C01) and K = 2 / D1 (visco2d_material's
!> shear and bulk of the material, so that KINEMATICS SMALL runs the same
!> flesh linearised).
!>
!> The stress is split into its isochoric part, from W_iso(bbar), and the
!> pressure p = U'(J) of U = (J - 1)^2 / D1, because the mean-dilatation
!> element (FORMULATION BBAR) evaluates the pressure from the element's
!> volume ratio instead of the point's J. Kirchhoff stress (Simo and Hughes
!> 1998, Computational Inelasticity, ch. 9; Holzapfel 2000, Nonlinear
!> Solid Mechanics, sec. 6.6):
!>
!>   taubar = 2 (C10 + I1bar C01) bbar - 2 C01 bbar^2,   tau_iso = dev taubar,   tau_vol = J p 1,
!>
!> and the spatial elasticity tensor (the push-forward of 4 d2W/dCdC, over J)
!>
!>   J c_iso = P : J cbar : P + 2/3 tr(taubar) P - 2/3 (tau_iso (x) 1 + 1 (x) tau_iso),
!>   J cbar  = 4 C01 (bbar (x) bbar - I_bbar),      P = I - 1/3 1 (x) 1,
!>   J c_vol = J (p + J U'') 1 (x) 1 - 2 J p I,
!>
!> I the symmetric fourth-order identity, I_bbar its push-forward by bbar
!> ((I_bbar)_ijkl = (bbar_ik bbar_jl + bbar_il bbar_jk) / 2). Stresses and
!> tangents are returned in the element's Voigt order (rr, zz, theta theta,
!> rz); the tangent's shear row and column are those of the (1, 2) pair,
!> D(4, 4) = c_1212 (the B matrix carries the engineering shear).
!> test/test_finite.f90 checks them against differences of the energy and of
!> the stress, and the uniaxial and volumetric closed forms.
module visco2d_hyperelastic
  use visco2d_kinds, only: dp
  implicit none
  private

  public :: hyperelastic_t, hyperelastic_from_moduli, isochoric_response, volumetric_response, hyperelastic_response
  public :: pressure_tangent, voigt_stress, voigt_tangent, identity3, volume_change, power_minus_one

  real(dp), parameter :: identity3(3, 3) = reshape([1.0_dp, 0.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, &
                                                    0.0_dp, 0.0_dp, 1.0_dp], [3, 3])
  integer, parameter :: voigt_i(4) = [1, 2, 3, 1], voigt_j(4) = [1, 2, 3, 2]

  !> The constants of W (Pa, 1/Pa); C01 = 0 is neo-Hookean.
  type :: hyperelastic_t
    real(dp) :: c10 = 0.0_dp   !< C10, Pa (> 0 with C01 >= 0, or C10 + C01 > 0)
    real(dp) :: c01 = 0.0_dp   !< C01, Pa (Mooney-Rivlin)
    real(dp) :: d1 = 0.0_dp    !< D1 = 2 / K, 1/Pa (> 0)
  end type hyperelastic_t

contains

  !> The neo-Hookean law with the small-strain moduli G (Pa) and K (Pa):
  !> C10 = G / 2, D1 = 2 / K.
  pure function hyperelastic_from_moduli(shear, bulk) result(law)
    real(dp), intent(in) :: shear, bulk
    type(hyperelastic_t) :: law
    law%c10 = 0.5_dp*shear
    law%c01 = 0.0_dp
    law%d1 = 2.0_dp/bulk
  end function hyperelastic_from_moduli

  !> The isochoric part at the deformation gradient F (3 x 3; in the
  !> element F(1:2, 1:2) is the in-plane block, F(3, 3) the hoop stretch):
  !> Cauchy stress sigma_iso = tau_iso / J (Voigt, Pa), the spatial tangent
  !> c_iso (Voigt, Pa) and W_iso per unit reference volume (J/m^3).
  pure subroutine isochoric_response(law, deformation, stress, tangent, energy, gradient)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: deformation(3, 3)
    real(dp), intent(out) :: stress(4), tangent(4, 4)
    real(dp), intent(out), optional :: energy
    real(dp), intent(in), optional :: gradient(3, 3)  !< H = F - I, computed without the cancellation of F - I
    real(dp) :: h(3, 3), jacobian, scale, bbar(3, 3), deviation(3, 3), bbar2_dev(3, 3), taubar(3, 3), tau(3, 3)
    real(dp) :: i1_excess, i2_excess, trace_taubar, c(4, 4), projector(4, 4), fictitious(4, 4), trace_deviation
    ! The stress from bbar - I, never from bbar itself: at strains of 1e-7 (a small load) dev(bbar) would
    ! lose 7 digits to the cancellation of I; b - I = H + H^T + H H^T and J - 1 keep them all.
    if (present(gradient)) then
      h = gradient
    else
      h = deformation - identity3
    end if
    jacobian = 1.0_dp + volume_change(h)
    scale = jacobian**(-2.0_dp/3.0_dp)
    ! bbar - I = J^(-2/3) (b - I) + (J^(-2/3) - 1) I
    deviation = scale*(h + transpose(h) + matmul(h, transpose(h))) + &
                power_minus_one(volume_change(h), -2.0_dp/3.0_dp)*identity3
    trace_deviation = deviation(1, 1) + deviation(2, 2) + deviation(3, 3)
    bbar = identity3 + deviation
    i1_excess = trace_deviation                                           ! I1bar - 3
    i2_excess = 2.0_dp*trace_deviation + 0.5_dp*(trace_deviation**2 - sum(deviation*transpose(deviation)))
    ! taubar = 2 (C10 + I1bar C01) bbar - 2 C01 bbar^2; its deviator from bbar - I:
    ! dev bbar = dev(bbar - I), dev bbar^2 = dev(2 (bbar - I) + (bbar - I)^2)
    bbar2_dev = deviator3(2.0_dp*deviation + matmul(deviation, deviation))
    tau = 2.0_dp*(law%c10 + (3.0_dp + i1_excess)*law%c01)*deviator3(deviation) - 2.0_dp*law%c01*bbar2_dev
    taubar = 2.0_dp*(law%c10 + (3.0_dp + i1_excess)*law%c01)*bbar - 2.0_dp*law%c01*matmul(bbar, bbar)
    trace_taubar = taubar(1, 1) + taubar(2, 2) + taubar(3, 3)
    projector = symmetric_identity() - outer(voigt_stress(identity3), voigt_stress(identity3))/3.0_dp
    fictitious = 4.0_dp*law%c01*(outer(voigt_stress(bbar), voigt_stress(bbar)) - push_identity(bbar))
    c = double_contraction(projector, double_contraction(fictitious, projector)) &
        + 2.0_dp/3.0_dp*trace_taubar*projector &
        - 2.0_dp/3.0_dp*(outer(voigt_stress(tau), voigt_stress(identity3)) + &
                         outer(voigt_stress(identity3), voigt_stress(tau)))
    stress = voigt_stress(tau)/jacobian
    tangent = c/jacobian
    if (present(energy)) energy = law%c10*i1_excess + law%c01*i2_excess
  end subroutine isochoric_response

  !> J - 1 of F = I + H (the in-plane block and the hoop stretch), without cancellation.
  pure real(dp) function volume_change(h)
    real(dp), intent(in) :: h(3, 3)
    real(dp) :: in_plane
    in_plane = h(1, 1) + h(2, 2) + h(1, 1)*h(2, 2) - h(1, 2)*h(2, 1)   ! det(I + H_2x2) - 1
    volume_change = h(3, 3) + in_plane*(1.0_dp + h(3, 3))
  end function volume_change

  !> (1 + x)^a - 1 without cancellation: the binomial series to x^5 for
  !> |x| < 1e-3 (the remainder below 1e-15 of the result), else directly.
  pure real(dp) function power_minus_one(x, a) result(value)
    real(dp), intent(in) :: x, a
    real(dp) :: term
    integer :: k
    if (abs(x) >= 1.0e-3_dp) then
      value = (1.0_dp + x)**a - 1.0_dp
      return
    end if
    value = 0.0_dp
    term = 1.0_dp
    do k = 1, 5
      term = term*(a - real(k - 1, dp))/real(k, dp)*x
      value = value + term
    end do
  end function power_minus_one

  pure function deviator3(a) result(d)
    real(dp), intent(in) :: a(3, 3)
    real(dp) :: d(3, 3)
    d = a - (a(1, 1) + a(2, 2) + a(3, 3))/3.0_dp*identity3
  end function deviator3

  !> The volumetric part U = (J - 1)^2 / D1 at the volume ratio J > 0:
  !> the pressure p = U'(J) (Pa, positive in tension), its slope U''(J)
  !> (Pa) and U (J/m^3 of reference volume).
  pure subroutine volumetric_response(law, jacobian, pressure, slope, energy, change)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: jacobian
    real(dp), intent(out) :: pressure, slope
    real(dp), intent(out), optional :: energy
    real(dp), intent(in), optional :: change   !< J - 1 computed without cancellation (else from jacobian)
    real(dp) :: excess
    excess = jacobian - 1.0_dp
    if (present(change)) excess = change
    pressure = 2.0_dp*excess/law%d1
    slope = 2.0_dp/law%d1
    if (present(energy)) energy = excess**2/law%d1
  end subroutine volumetric_response

  !> The whole law at F, the pressure from the point's own J: Cauchy
  !> stress, spatial tangent (Voigt, Pa) and W (J/m^3 of reference volume).
  pure subroutine hyperelastic_response(law, deformation, stress, tangent, energy, gradient)
    type(hyperelastic_t), intent(in) :: law
    real(dp), intent(in) :: deformation(3, 3)
    real(dp), intent(out) :: stress(4), tangent(4, 4)
    real(dp), intent(out), optional :: energy
    real(dp), intent(in), optional :: gradient(3, 3)  !< H = F - I without cancellation (isochoric_response)
    real(dp) :: jacobian, pressure, slope, isochoric_energy, volumetric_energy, change
    if (present(gradient)) then
      call isochoric_response(law, deformation, stress, tangent, isochoric_energy, gradient)
      change = volume_change(gradient)
    else
      call isochoric_response(law, deformation, stress, tangent, isochoric_energy)
      change = volume_change(deformation - identity3)
    end if
    jacobian = 1.0_dp + change
    call volumetric_response(law, jacobian, pressure, slope, volumetric_energy, change)
    stress(1:3) = stress(1:3) + pressure
    ! J c_vol / J = (p + J U'') 1 (x) 1 - 2 p I
    tangent = tangent + pressure_tangent(pressure) + jacobian*slope*outer(voigt_stress(identity3), &
                                                                          voigt_stress(identity3))
    if (present(energy)) energy = isochoric_energy + volumetric_energy
  end subroutine hyperelastic_response

  !> The spatial tangent of a pressure p held fixed: p (1 (x) 1 - 2 I), Voigt.
  pure function pressure_tangent(pressure) result(tangent)
    real(dp), intent(in) :: pressure
    real(dp) :: tangent(4, 4)
    tangent = pressure*(outer(voigt_stress(identity3), voigt_stress(identity3)) - 2.0_dp*symmetric_identity())
  end function pressure_tangent

  !> A symmetric 3 x 3 tensor (in-plane block and hoop) as (11, 22, 33, 12).
  pure function voigt_stress(tensor) result(v)
    real(dp), intent(in) :: tensor(3, 3)
    real(dp) :: v(4)
    v = [tensor(1, 1), tensor(2, 2), tensor(3, 3), tensor(1, 2)]
  end function voigt_stress

  !> A fourth-order tensor with the minor symmetries, c(i, j, k, l), as the
  !> 4 x 4 Voigt matrix of the pairs (11, 22, 33, 12).
  pure function voigt_tangent(c) result(d)
    real(dp), intent(in) :: c(3, 3, 3, 3)
    real(dp) :: d(4, 4)
    integer :: a, b
    do b = 1, 4
      do a = 1, 4
        d(a, b) = c(voigt_i(a), voigt_j(a), voigt_i(b), voigt_j(b))
      end do
    end do
  end function voigt_tangent

  !> The symmetric fourth-order identity (delta_ik delta_jl + delta_il delta_jk) / 2, Voigt.
  pure function symmetric_identity() result(d)
    real(dp) :: d(4, 4)
    d = push_identity(identity3)
  end function symmetric_identity

  !> (a_ik a_jl + a_il a_jk) / 2 for a symmetric a, Voigt.
  pure function push_identity(a) result(d)
    real(dp), intent(in) :: a(3, 3)
    real(dp) :: d(4, 4)
    integer :: p, q, i, j, k, l
    do q = 1, 4
      k = voigt_i(q)
      l = voigt_j(q)
      do p = 1, 4
        i = voigt_i(p)
        j = voigt_j(p)
        d(p, q) = 0.5_dp*(a(i, k)*a(j, l) + a(i, l)*a(j, k))
      end do
    end do
  end function push_identity

  !> A : B of two fourth-order tensors with the minor symmetries in this
  !> module's Voigt form (tensor components, the (1, 2) pair standing for
  !> both 12 and 21): the sum over the shear pair counts twice.
  pure function double_contraction(a, b) result(d)
    real(dp), intent(in) :: a(4, 4), b(4, 4)
    real(dp) :: d(4, 4)
    real(dp), parameter :: pair_weight(4) = [1.0_dp, 1.0_dp, 1.0_dp, 2.0_dp]
    d = matmul(a, spread(pair_weight, 2, 4)*b)
  end function double_contraction

  pure function outer(a, b) result(d)
    real(dp), intent(in) :: a(4), b(4)
    real(dp) :: d(4, 4)
    d = spread(a, 2, 4)*spread(b, 1, 4)
  end function outer

  pure real(dp) function determinant3(a)
    real(dp), intent(in) :: a(3, 3)
    determinant3 = a(1, 1)*(a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)) - a(1, 2)*(a(2, 1)*a(3, 3) - a(2, 3)*a(3, 1)) &
                   + a(1, 3)*(a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1))
  end function determinant3
end module visco2d_hyperelastic
