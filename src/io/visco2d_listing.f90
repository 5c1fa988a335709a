!> The legacy-style printed listing of a run (`listing.txt`): the input
!> cards, the control data, warnings, mesh, materials, time stages and
!> curves, node and element tables, supports and loads, and the results.
module visco2d_listing
  use visco2d_kinds, only: dp
  use visco2d_error, only: error_t, set_error
  use visco2d_strings, only: integer_text, table_real
  use visco2d_deck, only: deck_t, analysis_name, geometry_name, total_steps, analysis_dynamic, formulation_name, &
                          initial_velocity, stop_name
  use visco2d_material, only: material_kind_name, material_kind_elastic, material_kind_uniaxial, has_memory
  use visco2d_mesh, only: edge_set_name
  use visco2d_record, only: record_t, summary_item_text
  use visco2d_text_file, only: text_file_t, text_open, text_put, text_close
  implicit none
  private

  public :: write_listing, listing_row_limit

  !> Node and element tables in the listing stop after this many rows.
  integer, parameter :: listing_row_limit = 2000
  !> The rule between the listing's parts.
  character(len=*), parameter :: rule = repeat('-', 78)

contains

  !> The legacy-style printed listing; `error` (the file and what failed) if
  !> a write or the close failed.
  subroutine write_listing(path, case_name, deck, effects, record, error)
    character(*), intent(in) :: path, case_name, effects
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    type(error_t), allocatable, intent(out) :: error
    type(text_file_t) :: out
    call text_open(out, path)
    call listing_control(out, deck, case_name, effects)
    call listing_warnings(out, deck, record)
    call listing_model(out, deck)
    call listing_time(out, deck)
    call listing_mesh(out, deck)
    call listing_loads(out, deck)
    call listing_results(out, record)
    call text_put(out, rule)
    call text_close(out)
    if (len(out%message) > 0) call set_error(error, out%message, file=path)
  end subroutine write_listing

  !> The banner, the input cards as read and the control data of the run.
  subroutine listing_control(out, deck, case_name, effects)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: case_name, effects
    integer :: i
    call text_put(out, rule)
    call text_put(out, ' visco2d  -  axisymmetric / plane-strain viscoelastic finite elements')
    call text_put(out, rule)
    call text_put(out, ' case:  '//case_name)
    call text_put(out, ' title: '//deck%title)
    call text_put(out, ' deck:  '//deck%cards%file)
    call text_put(out, '')
    call text_put(out, ' INPUT CARDS')
    do i = 1, deck%cards%count
      call text_put(out, integer_field(deck%cards%cards(i)%line, 6)//'  '//deck%cards%cards(i)%text)
    end do
    call text_put(out, '')
    call text_put(out, ' CONTROL')
    call text_put(out, '   analysis          '//analysis_name(deck%analysis))
    call text_put(out, '   geometry          '//geometry_name(deck%settings%geometry))
    call text_put(out, '   effects           '//effects)
    call text_put(out, '   formulation       '//formulation_name(deck%settings%formulation))
    if (deck%analysis == analysis_dynamic) then
      call text_put(out, '   Wilson theta      '//table_real(deck%dynamics%theta))
      associate (velocity => initial_velocity(deck))
      call text_put(out, '   initial velocity  ('//table_real(velocity(1))//', '//table_real(velocity(2))//') m/s')
      end associate
      if (any(deck%dynamics%acceleration_given)) call text_put(out, '   initial accel.    ('// &
        table_real(deck%dynamics%acceleration(1))//', '//table_real(deck%dynamics%acceleration(2))//') m/s^2 (as given)')
      if (.not. all(deck%dynamics%acceleration_given)) call text_put(out, &
        '   initial accel.    from equilibrium M a = R(0) + gravity (components not given)')
      call text_put(out, '   output            history every '//integer_text(deck%output%every)//' step(s), '// &
        integer_text(size(deck%output%field_times))//' requested field time(s)')
    end if
    if (deck%loads%gravity > 0.0_dp) call text_put(out, &
      '   gravity           '//table_real(deck%loads%gravity)//' m/s^2 in -z')
    if (deck%plate%line > 0) then
      call text_put(out, '   plate             z = '//table_real(deck%plate%z)//' m, '// &
        trim(merge('STICK (u_r, u_z held)', 'SLIP (u_z held)      ', deck%plate%stick))//', RELEASE='// &
        trim(merge('YES', 'NO ', deck%plate%release)))
      if (deck%analysis == analysis_dynamic) call text_put(out, '   stop at           '//stop_name(deck%stop_at))
    end if
  end subroutine listing_control

  !> The deck's and the run's warnings, if any.
  subroutine listing_warnings(out, deck, record)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    type(record_t), intent(in) :: record
    integer :: k
    if (size(deck%warnings) + run_warnings(record) > 0) then
      call text_put(out, '')
      call text_put(out, ' WARNINGS')
      do k = 1, size(deck%warnings)
        call text_put(out, '   '//deck%warnings(k)%text)
      end do
      do k = 1, run_warnings(record)
        call text_put(out, '   '//record%warnings(k)%text)
      end do
    end if
  end subroutine listing_warnings

  !> The mesh size and the materials with their relaxation terms.
  subroutine listing_model(out, deck)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    integer :: i, k
    associate (mesh => deck%mesh)
    call text_put(out, '')
    call text_put(out, ' MESH')
    call text_put(out, '   source            '//mesh%source)
    call text_put(out, '   nodes             '//integer_text(mesh%nnode))
    call text_put(out, '   elements          '//integer_text(mesh%nelem))
    call text_put(out, '   equations         '//integer_text(2*mesh%nnode))
    call text_put(out, '   half-bandwidth    '//integer_text(mesh%half_bandwidth_before)//' as input, '// &
                  integer_text(mesh%half_bandwidth)//' after reverse Cuthill-McKee')
    call text_put(out, '')
    call text_put(out, ' MATERIALS')
    call text_put(out, '   id           kind          E(0) (Pa)       nu(0)     G(0) (Pa)       K (Pa)          rho (kg/m3)')
    do k = 1, size(deck%materials)
      associate (m => deck%materials(k))
      call text_put(out, '   '//text_field(m%id, 12)//' '//text_field(material_kind_name(m%kind), 12)//' '// &
        real_field(m%young, 15, 7)//' '//real_field(m%poisson, 9, 2, fixed=6)//' '//real_field(m%shear, 15, 7)//' '// &
        real_field(m%bulk, 15, 7)//' '//real_field(m%density, 15, 7))
      if (m%kind == material_kind_uniaxial) then
        call text_put(out, '     uniaxial relaxation E(t) = sum E_i exp(-alpha_i t), eq. [47], as given:')
        do i = 1, size(m%uniaxial_young)
          call text_put(out, '       E_i = '//real_field(m%uniaxial_young(i), 16, 8)//' Pa   alpha_i = '// &
            real_field(m%uniaxial_rate(i), 16, 8)//' 1/s')
        end do
        call text_put(out, '     converted exactly (eq. [48], partial fractions) to the shear terms below')
      end if
      if (m%kind /= material_kind_elastic) then
        call text_put(out, '     shear relaxation phi1(t) = G_inf + sum G_m exp(-beta_m t), eq. [12]:')
        call text_put(out, '       G_inf = '//real_field(m%long_term_shear, 16, 8)//' Pa')
        if (has_memory(m)) then
          do i = 1, size(m%prony_shear)
            call text_put(out, '       G_m = '//real_field(m%prony_shear(i), 16, 8)//' Pa   beta_m = '// &
              real_field(m%prony_rate(i), 16, 8)//' 1/s')
          end do
        end if
      end if
      if (m%plastic) then                           ! PLASTIC: the hardening curve as the solver reads it
        call text_put(out, '     von Mises plasticity (PLASTIC), isotropic hardening sigma_y(ebar), piecewise linear:')
        do i = 1, size(m%hardening%stress)
          call text_put(out, '       ebar = '//real_field(m%hardening%plastic_strain(i), 16, 8)//'   sigma_y = '// &
            real_field(m%hardening%stress(i), 16, 8)//' Pa')
        end do
        call text_put(out, '       slope beyond the last point '//real_field(m%hardening%final_slope, 16, 8)//' Pa')
      end if
      end associate
    end do
    end associate
  end subroutine listing_model

  !> The time stages and the curves.
  subroutine listing_time(out, deck)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    integer :: i, k
    if (size(deck%stages) > 0) then
      call text_put(out, '')
      call text_put(out, ' TIME STAGES  (line, steps, dt (s), end (s))')
      do k = 1, size(deck%stages)
        call text_put(out, integer_field(deck%stages(k)%line, 9)//integer_field(deck%stages(k)%steps, 9)//' '// &
          real_field(deck%stages(k)%dt, 16, 8)//' '//real_field(deck%stages(k)%end_time, 16, 8))
      end do
      if (deck%analysis == analysis_dynamic) then
        call text_put(out, '   '//integer_text(total_steps(deck))//' Wilson-theta steps from the initial state at t = 0')
      else
        call text_put(out, '   '//integer_text(total_steps(deck))//' steps after the instantaneous response at t = 0')
      end if
    end if
    if (size(deck%loads%curves) > 0) then
      call text_put(out, '')
      call text_put(out, ' CURVES  (name: time (s) -> factor; constant outside the points)')
      do k = 1, size(deck%loads%curves)
        call text_put(out, '   '//deck%loads%curves(k)%name//':')
        do i = 1, size(deck%loads%curves(k)%time)
          call text_put(out, '       '//real_field(deck%loads%curves(k)%time(i), 16, 8)//' -> '// &
            real_field(deck%loads%curves(k)%value(i), 16, 8))
        end do
      end do
    end if
  end subroutine listing_time

  !> The node and element tables (up to listing_row_limit rows each).
  subroutine listing_mesh(out, deck)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    integer :: i, k
    character(:), allocatable :: line
    associate (mesh => deck%mesh)
    call text_put(out, '')
    call text_put(out, ' NODES  (number, r (m), z (m), band position)')
    do i = 1, min(mesh%nnode, listing_row_limit)
      call text_put(out, integer_field(mesh%node_id(i), 9)//' '//real_field(mesh%xy(1, i), 16, 8)//' '// &
        real_field(mesh%xy(2, i), 16, 8)//integer_field(mesh%equation(i), 9))
    end do
    if (mesh%nnode > listing_row_limit) call text_put(out, '   ... '//integer_text(mesh%nnode - listing_row_limit)// &
      ' more nodes: see results.h5 /mesh/nodes')
    call text_put(out, '')
    call text_put(out, ' ELEMENTS  (number, nodes 1-4, material)')
    do i = 1, min(mesh%nelem, listing_row_limit)
      line = integer_field(mesh%element_id(i), 9)
      do k = 1, 4
        line = line//integer_field(mesh%node_id(mesh%connectivity(k, i)), 9)
      end do
      call text_put(out, line//'  '//trim(mesh%element_material_name(i)))
    end do
    if (mesh%nelem > listing_row_limit) call text_put(out, '   ... '//integer_text(mesh%nelem - listing_row_limit)// &
      ' more elements: see results.h5 /mesh/elements')
    end associate
  end subroutine listing_mesh

  !> The supports and the loads.
  subroutine listing_loads(out, deck)
    type(text_file_t), intent(inout) :: out
    type(deck_t), intent(in) :: deck
    integer :: k
    associate (mesh => deck%mesh)
    call text_put(out, '')
    call text_put(out, ' SUPPORTS AND LOADS')
    do k = 1, size(deck%loads%fixes)
      call text_put(out, '   FIX      line '//integer_text(deck%loads%fixes(k)%line)//': '// &
        integer_text(size(deck%loads%fixes(k)%nodes))// &
        ' node(s), '//merge('u_r ', '    ', deck%loads%fixes(k)%fix_r)//merge('u_z', '   ', &
          deck%loads%fixes(k)%fix_z)// &
        trim(prescribed_text(deck, k)))
    end do
    do k = 1, size(deck%loads%pressures)
      call text_put(out, '   PRESSURE line '//integer_text(deck%loads%pressures(k)%line)//': '// &
        edge_set_name(deck%loads%pressures(k)%edge_set)//' p = '//table_real(deck%loads%pressures(k)%value)//' Pa'// &
        curve_text(deck, deck%loads%pressures(k)%curve))
    end do
    do k = 1, size(deck%loads%forces)
      call text_put(out, '   FORCE    line '//integer_text(deck%loads%forces(k)%line)//': node '// &
        integer_text(mesh%node_id(deck%loads%forces(k)%node))//' F = ('//table_real(deck%loads%forces(k)%value(1))//', '// &
        table_real(deck%loads%forces(k)%value(2))//') N'//curve_text(deck, deck%loads%forces(k)%curve))
    end do
    end associate
  end subroutine listing_loads

  !> The summary and the first and last rows of the history.
  subroutine listing_results(out, record)
    type(text_file_t), intent(inout) :: out
    type(record_t), intent(in) :: record
    integer :: i, k
    character(:), allocatable :: line
    call text_put(out, '')
    call text_put(out, ' RESULTS')
    do i = 1, record%nsummary
      call text_put(out, '   '//trim(record%summary(i)%key)//' = '//summary_item_text(record%summary(i)))
    end do
    if (record%nrow > 0) then
      call text_put(out, '')
      call text_put(out, ' HISTORY (first and last rows; all rows in history.csv)')
      line = ''
      do k = 1, size(record%columns)
        line = line//text_field(record%columns(k)(1:min(16, len_trim(record%columns(k)))), 16, right=.true.)
        if (k < size(record%columns)) line = line//' '
      end do
      call text_put(out, line)
      do i = 1, record%nrow
        if (i > 20 .and. i < record%nrow - 20) cycle
        line = ''
        do k = 1, size(record%columns)
          line = line//real_field(record%history(k, i), 16, 8)
        if (k < size(record%columns)) line = line//' '
        end do
        call text_put(out, line)
      end do
    end if
  end subroutine listing_results

  !> A real right-aligned in `width` characters: es format with `digits`
  !> decimals and a 3-digit exponent (with its letter: 1.0E+300, never
  !> 1.0+300), or f format with `fixed` decimals where that fits; never '*'.
  function real_field(value, width, digits, fixed) result(text)
    real(dp), intent(in) :: value
    integer, intent(in) :: width, digits
    integer, intent(in), optional :: fixed
    character(:), allocatable :: text
    character(len=64) :: buffer
    character(len=32) :: form
    if (present(fixed)) then
      write(form, '(a, i0, a, i0, a)') '(f', width, '.', fixed, ')'
      write(buffer, form) value
      if (index(buffer(1:width), '*') == 0) then
        text = buffer(1:width)
        return
      end if
    end if
    write(form, '(a, i0, a)') '(es32.', digits, 'e3)'
    write(buffer, form) value
    text = text_field(trim(adjustl(buffer)), width, right=.true.)
  end function real_field

  !> An integer right-aligned in `width` characters (wider if it needs more).
  function integer_field(value, width) result(text)
    integer, intent(in) :: value, width
    character(:), allocatable :: text
    text = text_field(integer_text(value), width, right=.true.)
  end function integer_field

  !> Text padded with blanks to `width` (left-aligned, or right-aligned); longer text is kept whole.
  pure function text_field(text, width, right) result(field)
    character(*), intent(in) :: text
    integer, intent(in) :: width
    logical, intent(in), optional :: right
    character(:), allocatable :: field
    logical :: to_right
    to_right = .false.
    if (present(right)) to_right = right
    if (len(text) >= width) then
      field = text
    else if (to_right) then
      field = repeat(' ', width - len(text))//text
    else
      field = text//repeat(' ', width - len(text))
    end if
  end function text_field

  !> Number of run-time warnings in a record.
  pure integer function run_warnings(record)
    type(record_t), intent(in) :: record
    run_warnings = 0
    if (allocated(record%warnings)) run_warnings = size(record%warnings)
  end function run_warnings

  !> ' x curve NAME' or '' (constant in time).
  function curve_text(deck, curve) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: curve
    character(:), allocatable :: text
    text = ''
    if (curve > 0) text = ' x curve '//deck%loads%curves(curve)%name
  end function curve_text

  !> ', prescribed u_r = .., u_z = .. m [x curve]' for a FIX card with values.
  function prescribed_text(deck, k) result(text)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: k
    character(:), allocatable :: text
    text = ''
    associate (fix => deck%loads%fixes(k))
    if (all(fix%value == 0.0_dp)) return
    text = ', prescribed'
    if (fix%fix_r) text = text//' u_r = '//table_real(fix%value(1))//' m'
    if (fix%fix_z) text = text//' u_z = '//table_real(fix%value(2))//' m'
    text = text//curve_text(deck, fix%curve)
    end associate
  end function prescribed_text
end module visco2d_listing
