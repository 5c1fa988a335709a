!> Bruise prediction: time envelopes of failure measures at every Gauss point
!> and the region where the criterion of a BRUISE card reaches its threshold.
!>
!> For each Gauss point the module keeps the largest value over the run, and
!> the time it was reached, of
!>   1. the maximum shear stress (Tresca) (sigma_1 - sigma_3)/2, the hoop
!>      stress sigma_theta being a principal stress in axisymmetry, Pa;
!>   2. the von Mises stress, Pa;
!>   3. the octahedral shear stress sqrt(2)/3 sigma_Mises, Pa;
!>   4. the strain-energy density stored in the springs, J/m^3: K theta^2/2 +
!>      G_inf e:e + sum_m G_m C_m:C_m (eq. [12]'s terms; 1/2 sigma:epsilon for
!>      an elastic material), the density of the solver's strain_energy_J.
!> A point is bruised when the envelope of its card's criterion reaches the
!> threshold; with CRITERION=PLASTIC when its equivalent plastic strain (a
!> PLASTIC material, which never decreases: its own envelope) exceeds it. Volumes are 2 pi sum |J| r over the bruised Gauss points (the
!> element's own 2 x 2 rule, weights 1): whole body in axisymmetry, per metre
!> of thickness in plane strain.
!>
!> bruise_update takes the state its caller gives: a dynamic run gives the
!> state where the integrator holds equilibrium (Wilson-theta's solve point
!> t + theta dt, visco2d_time_step's solve_point_state; the step's end
!> otherwise), free of the overshoot Wilson-theta's t + dt carries after a
!> node is arrested on the plate.
!>
!> The envelopes are also kept for a deck with OUTPUT ENVELOPES=YES and no
!> BRUISE card, and for a dynamic deck with a PLASTIC material: then the
!> envelope maxima and fields are reported, and no bruise (threshold) measures. Nothing is allocated or computed for a deck
!> with neither.
module visco2d_bruise
  use visco2d_kinds, only: dp, geometry_axisymmetric
  use visco2d_deck, only: deck_t, stop_at_separation
  use visco2d_record, only: record_t, gauss_field_t, record_put, record_put_real, record_put_integer, record_real
  use visco2d_element, only: gauss_count, element_b_matrices, element_gauss_points
  use visco2d_material, only: von_mises, max_shear
  use visco2d_viscoelastic, only: viscoelastic_state_t, element_terms, stored_energy_density
  use visco2d_bruise_cards, only: criterion_name, criterion_unit, criterion_energy, criterion_plastic
  use visco2d_strings, only: integer_text
  use visco2d_pad_mesh, only: is_pad_element, body_nodes, body_elements
  implicit none
  private

  public :: bruise_t, bruise_update, bruise_report, bruise_static, measure_count, measure_names, envelopes_wanted, &
            bruise_plastic_field

  integer, parameter :: measure_count = 4   !< max shear, von Mises, octahedral, energy density
  !> Names of the measures as fields and keys (in the order of the criterion codes).
  character(len=15), parameter :: measure_names(measure_count) = [character(len=15) :: 'max_shear', &
    'von_mises', 'octahedral', 'energy_density']
  real(dp), parameter :: pi = 3.14159265358979323846264338327950288_dp
  real(dp), parameter :: never = -1.0_dp    !< time of a maximum or a failure that did not happen

  !> The envelopes of one run (allocated at the first bruise_update of a deck with BRUISE cards).
  type :: bruise_t
    logical :: active = .false.
    real(dp), allocatable :: envelope(:, :, :)   !< (measure_count, gauss_count, nelem), Pa or J/m^3
    real(dp), allocatable :: time_of_max(:, :, :)!< (measure_count, gauss_count, nelem), s (deck time)
    real(dp), allocatable :: failure_time(:, :)  !< (gauss_count, nelem) first time at the threshold, s; -1: never
    integer, allocatable :: rule(:)              !< (nelem) the deck's BRUISE card for the element; 0: none
    real(dp), allocatable :: volume(:, :)        !< (gauss_count, nelem) m^3 (per metre in plane strain)
    real(dp), allocatable :: point(:, :, :)      !< (2, gauss_count, nelem) undeformed r, z of the Gauss points, m
    real(dp) :: pole_z = 0.0_dp                  !< z of the body's lowest node (the undeformed contact pole), m
    real(dp), allocatable :: plastic(:, :)       !< (gauss_count, nelem) ebar at the last update (a PLASTIC material)
  end type bruise_t

contains

  !> Update the envelopes with the stresses and strains standing at `time`
  !> (a no-op unless envelopes_wanted). `state`: the viscoelastic history, if
  !> any; `plastic`: the equivalent plastic strain of a run with a PLASTIC material.
  subroutine bruise_update(bruise, deck, time, stress, strain, state, plastic)
    type(bruise_t), intent(inout) :: bruise
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: time
    real(dp), intent(in) :: stress(:, :, :), strain(:, :, :)   !< (4, gauss_count, nelem)
    type(viscoelastic_state_t), intent(in), optional :: state
    real(dp), intent(in), optional :: plastic(:, :)            !< (gauss_count, nelem)
    real(dp) :: values(measure_count)
    integer :: e, g, m
    if (.not. envelopes_wanted(deck)) return
    if (.not. bruise%active) call bruise_start(bruise, deck)
    if (present(plastic)) bruise%plastic = plastic
    do e = 1, deck%mesh%nelem
      do g = 1, gauss_count
        associate (s => stress(:, g, e))
        values(1) = max_shear(s(1), s(2), s(3), s(4))
        values(2) = von_mises(s(1), s(2), s(3), s(4))
        values(3) = sqrt(2.0_dp)/3.0_dp*values(2)
        end associate
        values(4) = energy_density(deck, e, g, stress(:, g, e), strain(:, g, e), state)
        do m = 1, measure_count
          if (values(m) > bruise%envelope(m, g, e)) then
            bruise%envelope(m, g, e) = values(m)
            bruise%time_of_max(m, g, e) = time
          end if
        end do
        if (bruise%rule(e) == 0 .or. bruise%failure_time(g, e) >= 0.0_dp) cycle
        associate (card => deck%bruises(bruise%rule(e)))
        if (card%criterion == criterion_plastic) then
          if (present(plastic)) then
            if (plastic(g, e) > card%threshold) bruise%failure_time(g, e) = time
          end if
        else if (values(card%criterion) >= card%threshold) then
          bruise%failure_time(g, e) = time
        end if
        end associate
      end do
    end do
  end subroutine bruise_update

  !> A static run: its one state at t = 0, then the report.
  subroutine bruise_static(deck, stress, strain, record)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: stress(:, :, :), strain(:, :, :)
    type(record_t), intent(inout) :: record
    type(bruise_t) :: bruise
    if (.not. envelopes_wanted(deck)) return
    call bruise_update(bruise, deck, 0.0_dp, stress, strain)
    call bruise_report(bruise, deck, record)
  end subroutine bruise_static

  !> True for a deck with a BRUISE card or OUTPUT ENVELOPES=YES. A dynamic
  !> deck with a PLASTIC material and neither keeps no envelope: its
  !> equivalent plastic strain is written at the end (bruise_plastic_field).
  logical function envelopes_wanted(deck) result(wanted)
    type(deck_t), intent(in) :: deck
    wanted = deck%output%envelopes
    if (allocated(deck%bruises)) wanted = wanted .or. size(deck%bruises) > 0   ! unallocated: a deck built in code
  end function envelopes_wanted

  !> The fields of a run with a PLASTIC material that kept no envelopes (no
  !> BRUISE card, no OUTPUT ENVELOPES=YES): its equivalent plastic strain
  !> `ebar` at the end, which is its envelope (ebar never decreases), with
  !> the quadrature (volume weights, Gauss-point positions), into the record.
  subroutine bruise_plastic_field(deck, ebar, record)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: ebar(:, :)                         !< (gauss_count, nelem)
    type(record_t), intent(inout) :: record
    type(bruise_t) :: bruise
    call bruise_start(bruise, deck)
    bruise%plastic = ebar
    allocate(record%bruise_fields(0))
    call put_quadrature(bruise, deck, record)
  end subroutine bruise_plastic_field

  !> Allocate the envelopes (zero), the rule of every element, the volume
  !> weights and the Gauss-point positions.
  subroutine bruise_start(bruise, deck)
    type(bruise_t), intent(inout) :: bruise
    type(deck_t), intent(in) :: deck
    real(dp) :: b(4, 8, gauss_count), factor(gauss_count)
    integer :: e, k
    associate (mesh => deck%mesh)
    allocate(bruise%envelope(measure_count, gauss_count, mesh%nelem), &
             bruise%time_of_max(measure_count, gauss_count, mesh%nelem), &
             bruise%failure_time(gauss_count, mesh%nelem), bruise%rule(mesh%nelem), &
             bruise%volume(gauss_count, mesh%nelem), bruise%point(2, gauss_count, mesh%nelem))
    bruise%envelope = 0.0_dp
    bruise%time_of_max = never
    bruise%failure_time = never
    bruise%rule = 0
    do e = 1, mesh%nelem
      ! The card naming the element's material, else the card without MAT=
      ! (not for a PAD's element: the pad is assessed only by name).
      do k = 1, size(deck%bruises)
        if (deck%bruises(k)%material == deck%materials(mesh%element_material(e))%id) then
          bruise%rule(e) = k
        else if (len(deck%bruises(k)%material) == 0 .and. bruise%rule(e) == 0 .and. .not. is_pad_element(deck, e)) then
          bruise%rule(e) = k
        end if
      end do
      associate (xy => mesh%xy(:, mesh%connectivity(:, e)))
      call element_b_matrices(deck%settings%geometry, xy, b, factor)
      bruise%point(:, :, e) = element_gauss_points(xy)
      end associate
      bruise%volume(:, e) = factor                      ! |J| r (|J| in plane strain), Gauss weights 1
      if (deck%settings%geometry == geometry_axisymmetric) bruise%volume(:, e) = 2.0_dp*pi*factor
    end do
    bruise%pole_z = minval(mesh%xy(2, :body_nodes(deck)))         ! the body's, not a PAD's
    end associate
    bruise%active = .true.
  end subroutine bruise_start

  !> Stored strain-energy density at one Gauss point, J/m^3 (as strain_energy_J's integrand).
  real(dp) function energy_density(deck, e, g, stress, strain, state) result(density)
    type(deck_t), intent(in) :: deck
    integer, intent(in) :: e, g
    real(dp), intent(in) :: stress(4), strain(4)
    type(viscoelastic_state_t), intent(in), optional :: state
    integer :: nterm, slot
    nterm = 0
    if (present(state)) then
      if (allocated(state%first)) nterm = element_terms(state, e)
    end if
    if (nterm == 0) then                               ! elastic: 1/2 sigma : epsilon (gamma_rz engineering)
      density = 0.5_dp*dot_product(stress, strain)
      return
    end if
    slot = state%first(e) + (g - 1)*nterm
    density = stored_energy_density(deck%materials(deck%mesh%element_material(e)), strain, &
                                    state%history(:, slot:slot + nterm - 1))
  end function energy_density

  !> The bruise measures (with BRUISE cards) into the summary, and the
  !> envelope maxima and fields into the record.
  subroutine bruise_report(bruise, deck, record)
    type(bruise_t), intent(in) :: bruise
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    logical, allocatable :: bruised(:, :), assessed(:, :)
    integer :: k
    if (.not. bruise%active) return
    assessed = spread(bruise%rule > 0, 1, gauss_count)
    bruised = assessed .and. bruise%failure_time >= 0.0_dp
    if (size(deck%bruises) > 0) call put_bruise_measures()
    do k = 1, measure_count
      call put_envelope_maximum(k)
    end do
    call put_fields(bruise, deck, bruised, assessed, record)

  contains

    !> The BRUISE cards' criteria, thresholds and the bruised region's measures.
    subroutine put_bruise_measures()
      character(:), allocatable :: basis, names
      real(dp) :: volume, absorbed
      integer :: k, i, count_extra
      basis = 'cm3'
      if (deck%settings%geometry /= geometry_axisymmetric) basis = 'cm3_per_m'
      names = criterion_name(deck%bruises(1)%criterion)
      do k = 2, size(deck%bruises)
        names = names//','//criterion_name(deck%bruises(k)%criterion)
      end do
      call record_put(record, 'bruise_criterion', names)
      if (size(deck%bruises) == 1) call record_put_real(record, 'bruise_threshold_'// &
        unit_key(deck%bruises(1)%criterion), deck%bruises(1)%threshold)
      call record_put_real(record, 'bruise_assessed_volume_'//basis, 1.0e6_dp*sum(bruise%volume, mask=assessed))
      volume = 1.0e6_dp*sum(bruise%volume, mask=bruised)
      call record_put_real(record, 'bruise_volume_'//basis, volume)
      call record_put_integer(record, 'bruise_gauss_points', count(bruised))
      if (any(bruised)) then
        call record_put_real(record, 'bruise_depth_top_mm', 1.0e3_dp*(minval(bruise%point(2, :, :), bruised) - &
                                                                     bruise%pole_z))
        call record_put_real(record, 'bruise_depth_bottom_mm', 1.0e3_dp*(maxval(bruise%point(2, :, :), bruised) - &
                                                                        bruise%pole_z))
        call record_put_real(record, 'bruise_radius_max_mm', 1.0e3_dp*maxval(bruise%point(1, :, :), bruised))
        call record_put_real(record, 'bruise_time_first_s', minval(bruise%failure_time, bruised))
      end if
      count_extra = 0
      do k = 1, size(deck%bruises)
        count_extra = max(count_extra, size(deck%bruises(k)%extra))
      end do
      do i = 1, count_extra
        if (size(deck%bruises) == 1) call record_put_real(record, 'bruise_threshold_'//integer_text(i)//'_'// &
          unit_key(deck%bruises(1)%criterion), deck%bruises(1)%extra(i))
        call record_put_real(record, 'bruise_volume_threshold_'//integer_text(i)//'_'//basis, 1.0e6_dp*extra_volume(i))
      end do
      if (deck%settings%geometry == geometry_axisymmetric .and. deck%stop_at == stop_at_separation .and. &
          summary_value(record, 'energy_absorbed_J', absorbed)) then
        if (absorbed > 0.0_dp) call record_put_real(record, 'bruise_susceptibility_cm3_per_J', volume/absorbed)
      end if
    end subroutine put_bruise_measures

    !> Volume where the envelope reaches the card's i-th extra threshold, m^3.
    real(dp) function extra_volume(i) result(total)
      integer, intent(in) :: i
      integer :: e, g
      total = 0.0_dp
      do e = 1, deck%mesh%nelem
        if (bruise%rule(e) == 0) cycle
        associate (card => deck%bruises(bruise%rule(e)))
        if (size(card%extra) < i) cycle
        do g = 1, gauss_count
          if (card%criterion == criterion_plastic) then
            if (allocated(bruise%plastic)) then
              if (bruise%plastic(g, e) > card%extra(i)) total = total + bruise%volume(g, e)
            end if
          else if (bruise%envelope(card%criterion, g, e) >= card%extra(i)) then
            total = total + bruise%volume(g, e)
          end if
        end do
        end associate
      end do
    end function extra_volume

    !> envelope_<measure>_max_<unit>, its r, z, depth below the pole and time
    !> (over the body: a PAD's elements are left out).
    subroutine put_envelope_maximum(m)
      integer, intent(in) :: m
      integer :: at(2)
      character(:), allocatable :: prefix
      at = maxloc(bruise%envelope(m, :, :body_elements(deck)))
      prefix = 'envelope_'//trim(measure_names(m))
      call record_put_real(record, prefix//'_max_'//unit_key(m), bruise%envelope(m, at(1), at(2)))
      call record_put_real(record, prefix//'_r_mm', 1.0e3_dp*bruise%point(1, at(1), at(2)))
      call record_put_real(record, prefix//'_z_mm', 1.0e3_dp*bruise%point(2, at(1), at(2)))
      call record_put_real(record, prefix//'_depth_mm', 1.0e3_dp*(bruise%point(2, at(1), at(2)) - bruise%pole_z))
      call record_put_real(record, prefix//'_time_s', bruise%time_of_max(m, at(1), at(2)))
    end subroutine put_envelope_maximum
  end subroutine bruise_report

  !> 'Pa', 'J_m3' or 'strain' (a key's unit suffix) of a measure or criterion code.
  pure function unit_key(code) result(text)
    integer, intent(in) :: code
    character(:), allocatable :: text
    text = 'Pa'
    if (code == criterion_energy) text = 'J_m3'
    if (code == criterion_plastic) text = 'strain'
  end function unit_key

  !> A number of the summary by key as summary.txt shows it (false if absent or
  !> not a number): the susceptibility has always divided by the energy's 10
  !> digits (with the full-precision energy peach_drop's moves in its 10th digit).
  logical function summary_value(record, key, value) result(found)
    type(record_t), intent(in) :: record
    character(*), intent(in) :: key
    real(dp), intent(out) :: value
    call record_real(record, key, value, found, as_shown=.true.)
  end function summary_value

  !> The envelopes, their times, the bruised mask, the thresholds and the
  !> quadrature (volume weights, Gauss-point positions) as record fields.
  subroutine put_fields(bruise, deck, bruised, assessed, record)
    type(bruise_t), intent(in) :: bruise
    type(deck_t), intent(in) :: deck
    logical, intent(in) :: bruised(:, :), assessed(:, :)
    type(record_t), intent(inout) :: record
    real(dp), allocatable :: threshold(:, :)
    integer :: m, e
    allocate(record%bruise_fields(0))
    do m = 1, measure_count
      call add_field(record, deck, trim(measure_names(m))//'_envelope', criterion_unit(m), bruise%envelope(m, :, :))
      call add_field(record, deck, trim(measure_names(m))//'_time', 's', bruise%time_of_max(m, :, :))
    end do
    call put_quadrature(bruise, deck, record)
    if (size(deck%bruises) == 0) return                 ! OUTPUT ENVELOPES=YES alone: no threshold, no region
    allocate(threshold(gauss_count, deck%mesh%nelem))
    threshold = 0.0_dp
    do e = 1, deck%mesh%nelem
      if (bruise%rule(e) > 0) threshold(:, e) = deck%bruises(bruise%rule(e))%threshold
    end do
    call add_field(record, deck, 'threshold', 'Pa or J/m^3 (the criterion of the element''s BRUISE card); 0: not assessed', &
                   threshold)
    call add_field(record, deck, 'assessed', '1', merge(1.0_dp, 0.0_dp, assessed))
    call add_field(record, deck, 'bruised', '1', merge(1.0_dp, 0.0_dp, bruised))
    call add_field(record, deck, 'failure_time', 's (-1: never)', bruise%failure_time)
  end subroutine put_fields

  !> The quadrature (volume weights, Gauss-point positions) and, with a
  !> PLASTIC material, the equivalent plastic strain, as record fields.
  subroutine put_quadrature(bruise, deck, record)
    type(bruise_t), intent(in) :: bruise
    type(deck_t), intent(in) :: deck
    type(record_t), intent(inout) :: record
    call add_field(record, deck, 'volume_weight', merge('m^3      ', 'm^3 per m', &
                   deck%settings%geometry == geometry_axisymmetric), bruise%volume, .false.)
    call add_field(record, deck, 'gauss_r', 'm', bruise%point(1, :, :), .false.)
    call add_field(record, deck, 'gauss_z', 'm', bruise%point(2, :, :), .false.)
    if (allocated(bruise%plastic)) call add_field(record, deck, 'equivalent_plastic_strain', '1', bruise%plastic)
  end subroutine put_quadrature

  !> A field into the record; with its nodal average unless `nodal` is false (the quadrature).
  subroutine add_field(record, deck, name, units, values, nodal)
    type(record_t), intent(inout) :: record
    type(deck_t), intent(in) :: deck
    character(*), intent(in) :: name, units
    real(dp), intent(in) :: values(:, :)
    logical, intent(in), optional :: nodal
    type(gauss_field_t) :: field
    field%name = name
    field%units = trim(units)
    field%gauss = values
    if (present(nodal)) then
      if (.not. nodal) then
        record%bruise_fields = [record%bruise_fields, field]
        return
      end if
    end if
    field%nodal = nodal_average(deck, values)
    record%bruise_fields = [record%bruise_fields, field]
  end subroutine add_field

  !> Nodal value: the mean over the node's elements of the Gauss point nearest
  !> the node (Gauss point c sits next to corner c): no extrapolation, so an
  !> envelope or a mask keeps its range.
  function nodal_average(deck, values) result(nodal)
    type(deck_t), intent(in) :: deck
    real(dp), intent(in) :: values(:, :)
    real(dp), allocatable :: nodal(:)
    integer, allocatable :: count(:)
    integer :: e, c, node
    allocate(nodal(deck%mesh%nnode), count(deck%mesh%nnode))
    nodal = 0.0_dp
    count = 0
    do e = 1, deck%mesh%nelem
      do c = 1, 4
        node = deck%mesh%connectivity(c, e)
        nodal(node) = nodal(node) + values(c, e)
        count(node) = count(node) + 1
      end do
    end do
    nodal = nodal/max(count, 1)
  end function nodal_average
end module visco2d_bruise
