!> The summary keys of a state's fields, written the same way by every
!> analysis: the largest displacement and the extreme stresses
!> (put_field_summary), the probes' displacements and nodal stresses
!> (put_probe_summary), and the stress fields of a snapshot.
module visco2d_field_summary
  use visco2d_kinds, only: dp
  use visco2d_mesh, only: mesh_t
  use visco2d_model, only: probe_t
  use visco2d_material, only: von_mises, max_shear
  use visco2d_assembly, only: nodal_average
  use visco2d_stress_recovery, only: node_stress
  use visco2d_record, only: record_t, snapshot_t, record_put_real
  implicit none
  private

  public :: set_snapshot_stress, put_field_summary, put_probe_summary

contains

  !> The stress fields of a snapshot from Gauss-point stresses: the Gauss
  !> values, their nodal averages, and the nodal maximum shear and von Mises stress.
  subroutine set_snapshot_stress(mesh, stress, snapshot)
    type(mesh_t), intent(in) :: mesh
    real(dp), intent(in) :: stress(:, :, :)
    type(snapshot_t), intent(inout) :: snapshot
    snapshot%stress_gauss = stress
    snapshot%stress = nodal_average(mesh, stress)
    snapshot%max_shear = max_shear(snapshot%stress(1, :), snapshot%stress(2, :), snapshot%stress(3, :), &
                                   snapshot%stress(4, :))
    snapshot%von_mises = von_mises(snapshot%stress(1, :), snapshot%stress(2, :), snapshot%stress(3, :), &
                                   snapshot%stress(4, :))
  end subroutine set_snapshot_stress

  !> Summary of a state: largest displacement, extreme stresses over the Gauss
  !> points. `prefix` (default none) names the state, e.g. 'end_'.
  subroutine put_field_summary(displacement, stress, record, prefix)
    real(dp), intent(in) :: displacement(:, :), stress(:, :, :)
    type(record_t), intent(inout) :: record
    character(*), intent(in), optional :: prefix
    character(:), allocatable :: p
    p = ''
    if (present(prefix)) p = prefix
    associate (s => stress)
    call record_put_real(record, p//'max_displacement_m', maxval(norm2(displacement, dim=1)))
    call record_put_real(record, p//'sigma_r_min_Pa', minval(s(1, :, :)))
    call record_put_real(record, p//'sigma_r_max_Pa', maxval(s(1, :, :)))
    call record_put_real(record, p//'sigma_z_min_Pa', minval(s(2, :, :)))
    call record_put_real(record, p//'sigma_z_max_Pa', maxval(s(2, :, :)))
    call record_put_real(record, p//'sigma_theta_min_Pa', minval(s(3, :, :)))
    call record_put_real(record, p//'sigma_theta_max_Pa', maxval(s(3, :, :)))
    call record_put_real(record, p//'tau_rz_max_abs_Pa', maxval(abs(s(4, :, :))))
    call record_put_real(record, p//'von_mises_max_Pa', maxval(von_mises(s(1, :, :), s(2, :, :), s(3, :, :), &
                                                                           s(4, :, :))))
    call record_put_real(record, p//'max_shear_max_Pa', maxval(max_shear(s(1, :, :), s(2, :, :), s(3, :, :), &
                                                                           s(4, :, :))))
    end associate
  end subroutine put_field_summary

  !> Summary keys probe_<name>_{r_m, z_m, ur_m, uz_m, sr_Pa, sz_Pa, st_Pa, trz_Pa} of a state.
  subroutine put_probe_summary(mesh, probes, displacement, stress, record)
    type(mesh_t), intent(in) :: mesh
    type(probe_t), intent(in) :: probes(:)
    real(dp), intent(in) :: displacement(:, :), stress(:, :, :)
    type(record_t), intent(inout) :: record
    integer :: p, node, c
    character(len=6), parameter :: probe_columns(6) = ['ur_m  ', 'uz_m  ', 'sr_Pa ', 'sz_Pa ', 'st_Pa ', 'trz_Pa']
    do p = 1, size(probes)
      node = probes(p)%node
      call record_put_real(record, 'probe_'//probes(p)%name//'_r_m', mesh%xy(1, node))
      call record_put_real(record, 'probe_'//probes(p)%name//'_z_m', mesh%xy(2, node))
      associate (values => [displacement(:, node), node_stress(mesh, stress, node)])
      do c = 1, 6
        call record_put_real(record, 'probe_'//probes(p)%name//'_'//trim(probe_columns(c)), values(c))
      end do
      end associate
    end do
  end subroutine put_probe_summary
end module visco2d_field_summary
