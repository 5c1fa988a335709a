!> Output of one run into its case folder: the legacy-style `listing.txt`,
!> `summary.txt` (`key = value`), `history.csv` and `results.h5`.
!> Names and keys here are an interface: tools parse them.
module visco2d_output
  use hdf5, only: hid_t
  use visco2d_kinds, only: dp
  use visco2d_strings, only: itoa, gtoa, es_field
  use visco2d_deck, only: deck_t, analysis_name, geometry_name, total_steps, analysis_dynamic, formulation_name, &
                          initial_velocity, stop_name
  use visco2d_material, only: material_kind_name, material_kind_elastic, material_kind_uniaxial, has_memory
  use visco2d_mesh, only: edge_set_name
  use visco2d_record, only: record_t
  use visco2d_hdf5, only: h5_writer_t, h5_open_file, h5_close_file, h5_group, h5_close_group, &
                          h5_write, h5_attribute
  implicit none
  private

  public :: write_summary, write_history, write_listing, write_results_h5, unit_of
  public :: listing_row_limit

  !> Node and element tables in the listing stop after this many rows.
  integer, parameter :: listing_row_limit = 2000

contains

  !> Unit of a history column or summary key, from its suffix ('t_ms' -> 'ms').
  pure function unit_of(name) result(unit)
    character(*), intent(in) :: name
    character(:), allocatable :: unit
    integer :: last
    last = index(trim(name), '_', back=.true.)
    unit = '1'
    if (last == 0) return
    if (len_trim(name) > 5) then
      if (name(len_trim(name) - 4:len_trim(name)) == '_m_s2') then
        unit = 'm/s^2'; return
      end if
    end if
    if (len_trim(name) > 4) then
      if (name(len_trim(name) - 3:len_trim(name)) == '_m_s') then
        unit = 'm/s'; return
      end if
    end if
    select case (trim(name(last + 1:)))
    case ('s', 'ms', 'm', 'mm', 'Pa', 'MPa', 'N', 'J', 'g')
      unit = trim(name(last + 1:))
    case ('m/s')
      unit = 'm/s'
    end select
  end function unit_of

  !> summary.txt: one `key = value` per line.
  subroutine write_summary(path, record, status)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    integer, intent(out) :: status
    integer :: unit, i
    open(newunit=unit, file=path, status='replace', action='write', iostat=status)
    if (status /= 0) return
    do i = 1, record%nsummary
      write(unit, '(a, " = ", a)', iostat=status) trim(record%summary(i)%key), record%summary(i)%value
    end do
    close(unit)
  end subroutine write_summary

  !> history.csv: a header row of column names (units in the names), then one row per output step.
  subroutine write_history(path, record, status)
    character(*), intent(in) :: path
    type(record_t), intent(in) :: record
    integer, intent(out) :: status
    integer :: unit, i, j
    character(:), allocatable :: line
    open(newunit=unit, file=path, status='replace', action='write', iostat=status)
    if (status /= 0) return
    line = trim(record%columns(1))
    do j = 2, size(record%columns)
      line = line//','//trim(record%columns(j))
    end do
    write(unit, '(a)') line
    do i = 1, record%nrow
      line = gtoa(record%history(1, i))
      do j = 2, size(record%columns)
        line = line//','//gtoa(record%history(j, i))
      end do
      write(unit, '(a)', iostat=status) line
    end do
    close(unit)
  end subroutine write_history

  !> The legacy-style printed listing.
  subroutine write_listing(path, case_name, deck, effects, record, status)
    character(*), intent(in) :: path, case_name, effects
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    integer, intent(out) :: status
    integer :: unit, i, k
    character(len=*), parameter :: rule = repeat('-', 78)
    open(newunit=unit, file=path, status='replace', action='write', iostat=status)
    if (status /= 0) return
    associate (mesh => deck%mesh)
    write(unit, '(a)') rule
    write(unit, '(a)') ' visco2d  -  axisymmetric / plane-strain viscoelastic finite elements'
    write(unit, '(a)') rule
    write(unit, '(a)') ' case:  '//case_name
    write(unit, '(a)') ' title: '//deck%title
    write(unit, '(a)') ' deck:  '//deck%cards%file
    write(unit, '(/, a)') ' INPUT CARDS'
    do i = 1, deck%cards%count
      write(unit, '(i6, 2x, a)') deck%cards%cards(i)%line, deck%cards%cards(i)%text
    end do
    write(unit, '(/, a)') ' CONTROL'
    write(unit, '(a)') '   analysis          '//analysis_name(deck%analysis)
    write(unit, '(a)') '   geometry          '//geometry_name(deck%geometry)
    write(unit, '(a)') '   effects           '//effects
    write(unit, '(a)') '   formulation       '//formulation_name(deck%formulation)
    if (deck%analysis == analysis_dynamic) then
      write(unit, '(a)') '   Wilson theta      '//gtoa(deck%dynamics%theta)
      associate (velocity => initial_velocity(deck))
      write(unit, '(a)') '   initial velocity  ('//gtoa(velocity(1))//', '//gtoa(velocity(2))//') m/s'
      end associate
      if (any(deck%dynamics%acceleration_given)) write(unit, '(a)') '   initial accel.    ('// &
        gtoa(deck%dynamics%acceleration(1))//', '//gtoa(deck%dynamics%acceleration(2))//') m/s^2 (as given)'
      if (.not. all(deck%dynamics%acceleration_given)) write(unit, '(a)') &
        '   initial accel.    from equilibrium M a = R(0) + gravity (components not given)'
      write(unit, '(a)') '   output            history every '//itoa(deck%output%every)//' step(s), '// &
        itoa(size(deck%output%field_times))//' requested field time(s)'
    end if
    if (deck%gravity > 0.0_dp) write(unit, '(a)') '   gravity           '//gtoa(deck%gravity)//' m/s^2 in -z'
    if (deck%plate%line > 0) then
      write(unit, '(a)') '   plate             z = '//gtoa(deck%plate%z)//' m, '// &
        trim(merge('STICK (u_r, u_z held)', 'SLIP (u_z held)      ', deck%plate%stick))//', RELEASE='// &
        trim(merge('YES', 'NO ', deck%plate%release))
      if (deck%analysis == analysis_dynamic) write(unit, '(a)') '   stop at           '//stop_name(deck%stop_at)
    end if
    if (size(deck%warnings) > 0) then
      write(unit, '(/, a)') ' WARNINGS'
      do k = 1, size(deck%warnings)
        write(unit, '(3x, a)') deck%warnings(k)%text
      end do
    end if
    write(unit, '(/, a)') ' MESH'
    write(unit, '(a)') '   source            '//mesh%source
    write(unit, '(a)') '   nodes             '//itoa(mesh%nnode)
    write(unit, '(a)') '   elements          '//itoa(mesh%nelem)
    write(unit, '(a)') '   equations         '//itoa(2*mesh%nnode)
    write(unit, '(a)') '   half-bandwidth    '//itoa(mesh%half_bandwidth_before)//' as input, '// &
                       itoa(mesh%half_bandwidth)//' after reverse Cuthill-McKee'
    write(unit, '(/, a)') ' MATERIALS'
    write(unit, '(a)') '   id           kind          E(0) (Pa)       nu(0)     G(0) (Pa)       K (Pa)          rho (kg/m3)'
    do k = 1, size(deck%materials)
      associate (m => deck%materials(k))
      write(unit, '(3x, a12, 1x, a12, 1x, a15, 1x, f9.6, 3(1x, a15))') m%id, material_kind_name(m%kind), &
        es_field(m%young, 15, 7), m%poisson, es_field(m%shear, 15, 7), es_field(m%bulk, 15, 7), &
        es_field(m%density, 15, 7)
      if (m%kind == material_kind_uniaxial) then
        write(unit, '(a)') '     uniaxial relaxation E(t) = sum E_i exp(-alpha_i t), eq. [47], as given:'
        do i = 1, size(m%uniaxial_young)
          write(unit, '(7x, a, a, a, a, a)') 'E_i = ', es_field(m%uniaxial_young(i), 16, 8), ' Pa   alpha_i = ', &
            es_field(m%uniaxial_rate(i), 16, 8), ' 1/s'
        end do
        write(unit, '(a)') '     converted exactly (eq. [48], partial fractions) to the shear terms below'
      end if
      if (m%kind /= material_kind_elastic) then
        write(unit, '(a)') '     shear relaxation phi1(t) = G_inf + sum G_m exp(-beta_m t), eq. [12]:'
        write(unit, '(7x, a, a, a)') 'G_inf = ', es_field(m%long_term_shear, 16, 8), ' Pa'
        if (has_memory(m)) then
          do i = 1, size(m%prony_shear)
            write(unit, '(7x, a, a, a, a, a)') 'G_m = ', es_field(m%prony_shear(i), 16, 8), ' Pa   beta_m = ', &
              es_field(m%prony_rate(i), 16, 8), ' 1/s'
          end do
        end if
      end if
      end associate
    end do
    if (size(deck%stages) > 0) then
      write(unit, '(/, a)') ' TIME STAGES  (line, steps, dt (s), end (s))'
      do k = 1, size(deck%stages)
        write(unit, '(i9, i9, 2(1x, a))') deck%stages(k)%line, deck%stages(k)%steps, &
          es_field(deck%stages(k)%dt, 16, 8), es_field(deck%stages(k)%end_time, 16, 8)
      end do
      if (deck%analysis == analysis_dynamic) then
        write(unit, '(a)') '   '//itoa(total_steps(deck))//' Wilson-theta steps from the initial state at t = 0'
      else
        write(unit, '(a)') '   '//itoa(total_steps(deck))//' steps after the instantaneous response at t = 0'
      end if
    end if
    if (size(deck%curves) > 0) then
      write(unit, '(/, a)') ' CURVES  (name: time (s) -> factor; constant outside the points)'
      do k = 1, size(deck%curves)
        write(unit, '(3x, a)') deck%curves(k)%name//':'
        do i = 1, size(deck%curves(k)%time)
          write(unit, '(7x, a, a, a)') es_field(deck%curves(k)%time(i), 16, 8), ' -> ', &
            es_field(deck%curves(k)%value(i), 16, 8)
        end do
      end do
    end if
    write(unit, '(/, a)') ' NODES  (number, r (m), z (m), band position)'
    do i = 1, min(mesh%nnode, listing_row_limit)
      write(unit, '(i9, 2(1x, a), i9)') mesh%node_id(i), es_field(mesh%xy(1, i), 16, 8), &
        es_field(mesh%xy(2, i), 16, 8), mesh%equation(i)
    end do
    if (mesh%nnode > listing_row_limit) write(unit, '(a)') '   ... '//itoa(mesh%nnode - listing_row_limit)// &
      ' more nodes: see results.h5 /mesh/nodes'
    write(unit, '(/, a)') ' ELEMENTS  (number, nodes 1-4, material)'
    do i = 1, min(mesh%nelem, listing_row_limit)
      write(unit, '(i9, 4i9, 2x, a)') mesh%element_id(i), mesh%node_id(mesh%connectivity(:, i)), &
        trim(mesh%element_material_name(i))
    end do
    if (mesh%nelem > listing_row_limit) write(unit, '(a)') '   ... '//itoa(mesh%nelem - listing_row_limit)// &
      ' more elements: see results.h5 /mesh/elements'
    write(unit, '(/, a)') ' SUPPORTS AND LOADS'
    do k = 1, size(deck%fixes)
      write(unit, '(a)') '   FIX      line '//itoa(deck%fixes(k)%line)//': '//itoa(size(deck%fixes(k)%nodes))// &
        ' node(s), '//merge('u_r ', '    ', deck%fixes(k)%fix_r)//merge('u_z', '   ', deck%fixes(k)%fix_z)// &
        trim(prescribed_text(deck, k))
    end do
    do k = 1, size(deck%pressures)
      write(unit, '(a)') '   PRESSURE line '//itoa(deck%pressures(k)%line)//': '// &
        edge_set_name(deck%pressures(k)%edge_set)//' p = '//gtoa(deck%pressures(k)%value)//' Pa'// &
        curve_text(deck, deck%pressures(k)%curve)
    end do
    do k = 1, size(deck%forces)
      write(unit, '(a)') '   FORCE    line '//itoa(deck%forces(k)%line)//': node '// &
        itoa(mesh%node_id(deck%forces(k)%node))//' F = ('//gtoa(deck%forces(k)%value(1))//', '// &
        gtoa(deck%forces(k)%value(2))//') N'//curve_text(deck, deck%forces(k)%curve)
    end do
    write(unit, '(/, a)') ' RESULTS'
    do i = 1, record%nsummary
      write(unit, '(3x, a, " = ", a)') trim(record%summary(i)%key), record%summary(i)%value
    end do
    if (record%nrow > 0) then
      write(unit, '(/, a)') ' HISTORY (first and last rows; all rows in history.csv)'
      write(unit, '(*(a16, :, 1x))') (trim(record%columns(k)), k = 1, size(record%columns))
      do i = 1, record%nrow
        if (i > 20 .and. i < record%nrow - 20) cycle
        write(unit, '(*(a16, :, 1x))') (es_field(record%history(k, i), 16, 8), k = 1, size(record%history, 1))
      end do
    end if
    write(unit, '(a)') rule
    end associate
    close(unit)
  end subroutine write_listing

  !> ' x curve NAME' or '' (constant in time).
  function curve_text(deck, curve) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: curve
    character(:), allocatable :: text
    text = ''
    if (curve > 0) text = ' x curve '//deck%curves(curve)%name
  end function curve_text

  !> ', prescribed u_r = .., u_z = .. m [x curve]' for a FIX card with values.
  function prescribed_text(deck, k) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: k
    character(:), allocatable :: text
    text = ''
    associate (fix => deck%fixes(k))
    if (all(fix%value == 0.0_dp)) return
    text = ', prescribed'
    if (fix%fix_r) text = text//' u_r = '//gtoa(fix%value(1))//' m'
    if (fix%fix_z) text = text//' u_z = '//gtoa(fix%value(2))//' m'
    text = text//curve_text(deck, fix%curve)
    end associate
  end function prescribed_text

  !> results.h5: /mesh, /history/<column>, /fields/<snapshot>/..., summary as root attributes.
  subroutine write_results_h5(path, case_name, deck, record, status)
    character(*), intent(in) :: path, case_name
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    integer, intent(out) :: status
    type(h5_writer_t) :: writer
    integer(hid_t) :: group, fields, snapshot
    integer :: i, k
    real(dp), allocatable :: column(:)

    call h5_open_file(writer, path)
    if (writer%status /= 0) then
      status = writer%status
      return
    end if
    call h5_attribute(writer, writer%file, 'case', case_name)
    call h5_attribute(writer, writer%file, 'title', deck%title)
    call h5_attribute(writer, writer%file, 'geometry', geometry_name(deck%geometry))
    call h5_attribute(writer, writer%file, 'analysis', analysis_name(deck%analysis))

    group = h5_group(writer, writer%file, 'mesh')
    call h5_write(writer, group, 'nodes', deck%mesh%xy, units='m')
    call h5_write(writer, group, 'elements', deck%mesh%connectivity)
    call h5_write(writer, group, 'node_ids', deck%mesh%node_id)
    call h5_write(writer, group, 'element_ids', deck%mesh%element_id)
    call h5_write(writer, group, 'element_material', deck%mesh%element_material)
    call h5_close_group(writer, group)

    group = h5_group(writer, writer%file, 'summary')
    do i = 1, record%nsummary
      call h5_attribute(writer, group, trim(record%summary(i)%key), record%summary(i)%value)
    end do
    call h5_close_group(writer, group)

    group = h5_group(writer, writer%file, 'history')
    do k = 1, size(record%columns)
      column = record%history(k, 1:record%nrow)
      call h5_write(writer, group, trim(record%columns(k)), column, units=unit_of(record%columns(k)))
    end do
    call h5_close_group(writer, group)

    fields = h5_group(writer, writer%file, 'fields')
    if (allocated(record%snapshots)) then
      do i = 1, size(record%snapshots)
        associate (s => record%snapshots(i))
        snapshot = h5_group(writer, fields, s%name)
        call h5_attribute(writer, snapshot, 'time', s%time)
        call h5_attribute(writer, snapshot, 'time_units', 's')
        call h5_attribute(writer, snapshot, 'label', s%label)
        call h5_write(writer, snapshot, 'displacement', s%displacement, units='m')
        if (allocated(s%velocity)) call h5_write(writer, snapshot, 'velocity', s%velocity, units='m/s')
        if (allocated(s%acceleration)) call h5_write(writer, snapshot, 'acceleration', s%acceleration, units='m/s^2')
        call h5_write(writer, snapshot, 'stress', s%stress, units='Pa')
        call h5_write(writer, snapshot, 'stress_gauss', s%stress_gauss, units='Pa')
        call h5_write(writer, snapshot, 'max_shear', s%max_shear, units='Pa')
        call h5_write(writer, snapshot, 'von_mises', s%von_mises, units='Pa')
        call h5_close_group(writer, snapshot)
        end associate
      end do
    end if
    call h5_close_group(writer, fields)
    call h5_close_file(writer)
    status = writer%status
  end subroutine write_results_h5
end module visco2d_output
