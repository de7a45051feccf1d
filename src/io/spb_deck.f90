!> The namelist deck (doc/deck.md): reading, validation, the problem it describes, echo.
!>
!> The variables themselves (name, default, unit, meaning, echo) are listed once, in
!> spb_deck_params; this module reads a deck group by group through that list and checks
!> the values against each other. Reading never stops the program: every problem comes
!> back as one error naming the group and the variable. Real inputs are tested for being
!> finite before any comparison (a NaN compared under -ffpe-trap=invalid would trap).
module spb_deck
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use spb_kinds, only: wp, max_segments, max_profiles, max_sweep_values, max_realizations, &
      name_len, max_gauges, max_ensemble_columns
   use spb_error, only: spb_error_t, make_error
   use spb_strings, only: itoa, rtoa, lower
   use spb_prescan, only: deck_scan_t, scan_deck, has_group, has_var, assignment_text, &
      group_preamble
   use spb_deck_types, only: deck_t, run_cfg, mesh_cfg, segments_cfg, ends_cfg, load_cfg, &
      deck_record_t, gauges_cfg, echo_item_t, known_groups, is_set, timing_words, shift_words, &
      events_words, model_words, fit_words, top_words, bottom_words, interface_words, &
      kind_words, face_words, state_words, field_words, distribution_words, header_words, &
      side_words
   use spb_deck_params, only: param_pass_t, deck_params, pass_read, pass_echo, pass_find, &
      pass_set, pass_doc, huge_real
   use spb_random, only: weibull_log_min, weibull_log_max
   use spb_columns, only: column_set_t
   use spb_history, only: history_set
   use spb_sys, only: fp_traps_off, fp_traps_restore
   use spb_mesh, only: mesh_fault_t, max_cells, max_steps, fault_cells, fault_segment_cells, &
      fault_not_whole, fault_short_segment, fault_mesh_cells, fault_short_run, fault_long_run
   use spb_problem, only: problem_t, end_free, end_fixed, end_transmit, end_base, end_velocity, &
      end_impactor, &
      load_none, load_power, load_table, load_exponential, face_top, face_bottom, &
      timing_accelerate, timing_delay, timing_min, timing_within, shift_above, shift_fragment, &
      shift_face, &
      events_admissible, events_paper
   implicit none
   private
   public :: deck_t, deck_record_t, known_groups
   public :: read_deck, validate_deck, write_echo, set_deck_value, deck_value, problem_from_deck, &
      deck_record, mesh_fault_message, write_deck_help, deck_file, deck_warnings

   !> The largest ratio of two segments' axial impedances rho a A a deck may hold: beyond it
   !> the wave measure (ledger_w, the energy guard) reads the side of the smaller one from
   !> differences of the other's round-off (doc/areas.md, "How far apart").
   real(wp), parameter :: max_impedance_ratio = 1.0e6_wp

contains

   !> The problem a validated deck describes: the keywords become codes, the "not given"
   !> markers defaults or logicals (a load table's rows are read by spb_load_table).
   function problem_from_deck(deck) result(prob)
      type(deck_t), intent(in) :: deck     !! the deck
      type(problem_t) :: prob
      integer :: n, j
      n = deck%seg%n
      prob%nseg = n
      allocate(prob%fracture_energy(n))
      prob%fracture_energy(:) = deck%seg%fracture_energy(1:n)
      allocate(prob%damage_integral(n), prob%damage_exponent(n))
      prob%damage_integral(:) = deck%seg%damage_integral(1:n)
      prob%damage_exponent(:) = deck%seg%damage_exponent(1:n)
      allocate(prob%length(n), prob%young(n), prob%density(n), prob%strength(n), &
               prob%velocity(n), prob%dry(n), prob%gap(n), prob%area(n))
      prob%length(:) = deck%seg%length(1:n)
      prob%young(:) = deck%seg%young(1:n)
      prob%density(:) = deck%seg%density(1:n)
      prob%area(:) = deck%seg%area(1:n)
      prob%strength(:) = deck%seg%strength(1:n)
      prob%velocity(:) = deck%seg%velocity(1:n)
      prob%dry = .false.
      prob%gap = 0.0_wp
      do j = 1, n - 1
         prob%dry(j) = deck%seg%interface(j) == 'dry'
         if (is_set(deck%seg%gap(j))) prob%gap(j) = deck%seg%gap(j)
      end do
      prob%cells = deck%mesh%cells
      prob%ref_segment = deck%mesh%ref_segment
      prob%dt = deck%mesh%dt
      prob%stretch = deck%mesh%fit == 'stretch'
      prob%t_end = deck%run%t_end
      prob%top = code_of(top_words, deck%ends%top, [end_free, end_fixed, end_transmit, &
                         end_velocity, end_base])
      prob%bottom = code_of(bottom_words, deck%ends%bottom, [end_free, end_fixed, end_base, &
                            end_transmit, end_velocity])
      prob%base_gap = deck%ends%base_gap
      prob%base_gap_top = deck%ends%base_gap_top
      if (deck%impactor%on) then
         prob%impactor_face = code_of(face_words, deck%impactor%face, [face_top, face_bottom])
         prob%impactor_mass = deck%impactor%mass
         prob%impactor_velocity = deck%impactor%velocity
         prob%impactor_gap = deck%impactor%gap
         prob%impactor_cushion = deck%impactor%cushion
         if (prob%impactor_face == face_top) then
            prob%top = end_impactor
         else
            prob%bottom = end_impactor
         end if
      end if
      prob%load_kind = code_of(kind_words, deck%load%kind, [load_none, load_power, &
                               load_exponential, load_table])
      prob%load_face = code_of(face_words, deck%load%face, [face_top, face_bottom])
      if (is_set(deck%load%p0)) prob%p0 = deck%load%p0
      prob%has_t_k = is_set(deck%load%t_k)
      if (prob%has_t_k) prob%t_k = deck%load%t_k
      prob%exponent = deck%load%exponent
      prob%has_t_cut = is_set(deck%load%t_cut)
      if (prob%has_t_cut) prob%t_cut = deck%load%t_cut
      prob%static_start = deck%init%state == 'static'
      prob%strain_rate = deck%init%strain_rate
      prob%weibull = deck%field%kind == 'weibull'
      if (is_set(deck%field%modulus)) prob%weibull_modulus = deck%field%modulus
      if (is_set(deck%field%scale)) prob%weibull_scale = deck%field%scale
      prob%seed = deck%field%seed
      prob%gravity = deck%run%gravity
      prob%full_mass = deck%run%model == 'full-mass'
      prob%timing = code_of(timing_words, deck%run%timing, [timing_accelerate, timing_delay, &
                            timing_min, timing_within])
      prob%shift = code_of(shift_words, deck%run%shift, [shift_above, shift_fragment, &
                           shift_face])
      prob%events = code_of(events_words, deck%run%events, [events_admissible, events_paper])
      prob%eps_rel = deck%run%eps_rel
   contains
      !> The code of a keyword: codes(k) for words(k) (codes(1), the default, if none).
      integer function code_of(words, word, codes)
         character(len=*), intent(in) :: words(:)   !! the keyword's values
         character(len=*), intent(in) :: word       !! the value given
         integer, intent(in) :: codes(:)            !! their codes, in the same order
         code_of = codes(max(1, findloc(words, word, 1)))
      end function code_of
   end function problem_from_deck

   !> Read and validate a deck file.
   subroutine read_deck(path, deck, err, sweep)
      character(len=*), intent(in) :: path       !! deck file
      type(deck_t), intent(out) :: deck    !! the deck
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      logical, intent(in), optional :: sweep     !! a sweep deck (--sweep): &sweep required
      integer :: g, k
      logical :: traps(3)

      call scan_deck(path, known_groups, deck%scan, err)
      if (allocated(err)) return
      deck%path = path
      if (.not. has_group(deck%scan, 'run')) then
         call make_error(err, '&run: required group is missing (it must give t_end)')
         return
      end if
      if (present(sweep)) deck%is_sweep = sweep
      if (has_group(deck%scan, 'sweep') .and. .not. deck%is_sweep) then
         call make_error(err, '&sweep: this deck is a sweep; run it with spallbar --sweep ' // &
                         trim(path) // ' (under mpirun for several ranks)')
         return
      end if
      if (deck%is_sweep .and. .not. has_group(deck%scan, 'sweep')) then
         call make_error(err, '&sweep: required group is missing (--sweep needs realizations ' &
                         // 'or vary and values)')
         return
      end if
      ! reading and validation compare values the user gave, NaN and Inf among them, before
      ! they reject them: the traps stay off until both are done
      call fp_traps_off(traps)
      do g = 1, size(known_groups)
         call read_group(deck, trim(known_groups(g)), err)
         if (allocated(err)) exit
      end do
      deck%impactor%on = has_group(deck%scan, 'impactor')
      if (.not. allocated(err)) then
         deck%sweep%n_values = 0
         do k = 1, max_sweep_values
            if (.not. is_set(deck%sweep%values(k))) exit
            deck%sweep%n_values = k
         end do
         deck%sweep%n_ensemble = 0
         do k = 1, size(deck%sweep%ensemble_columns)
            if (len_trim(deck%sweep%ensemble_columns(k)) == 0) exit
            deck%sweep%n_ensemble = k
         end do
         call validate_deck(deck, err)
      end if
      if (.not. allocated(err) .and. deck%is_sweep) call validate_sweep(deck, err)
      call fp_traps_restore(traps)
   end subroutine read_deck

   !> Read one group: its assignments in the deck's order, each by the one call in
   !> deck_params that answers to its name; the first that does not read is the error.
   subroutine read_group(deck, group, err)
      type(deck_t), intent(inout) :: deck   !! the deck
      character(len=*), intent(in) :: group   !! group name
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(param_pass_t) :: pass
      character(len=:), allocatable :: record, var
      integer :: k
      do k = 1, size(deck%scan%keys)
         record = assignment_text(deck%scan, group, k, var)
         if (len(record) == 0) cycle
         pass = param_pass_t(mode=pass_read, group=group, name=var, record=record)
         call deck_params(deck, pass)
         if (allocated(pass%err)) then
            call move_alloc(pass%err, err)
            return
         end if
         if (.not. pass%found) then
            call make_error(err, '&' // group // ': ' // var // ': unknown variable in this group')
            return
         end if
      end do
      call read_preamble(deck%scan, group, err)
   end subroutine read_group

   !> What stands in a group before its first assignment must read as nothing (only blanks,
   !> comments, separators): a stray word or number there is an error naming it.
   subroutine read_preamble(deck_scan, group, err)
      type(deck_scan_t), intent(in) :: deck_scan   !! the prescan of the deck
      character(len=*), intent(in) :: group   !! group name
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), parameter :: nomatch = 'Cannot match namelist object name '
      character(len=:), allocatable :: text, name
      character(len=256) :: msg
      integer :: ios, k
      real(wp) :: spb_none
      namelist /spb_value/ spb_none
      text = group_preamble(deck_scan, group)
      if (len_trim(text) == 0) return
      text = '&spb_value ' // text // ' /'
      read(text, nml=spb_value, iostat=ios, iomsg=msg)
      if (ios == 0) return
      k = index(msg, nomatch)
      if (k > 0) then
         name = lower(trim(adjustl(msg(k + len(nomatch):))))
         if (len(name) >= 2) then
            if (scan(name(1:1), '''"') > 0 .and. name(len(name):len(name)) == name(1:1)) then
               name = name(2:len(name)-1)
            end if
         end if
         k = scan(name, '(')
         if (k > 1) name = name(:k-1)
         call make_error(err, '&' // group // ': cannot read the value ''' // name // &
                         ''' (wrong type, unquoted text or too many values?)')
      else
         call make_error(err, '&' // group // ': cannot read the group: ' // trim(msg))
      end if
   end subroutine read_preamble

   !> &sweep: what to vary and how often; every case's deck must itself be valid.
   subroutine validate_sweep(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(deck_t) :: trial
      integer :: k
      associate (sw => deck%sweep)
         if (sw%realizations < 0 .or. sw%realizations > max_realizations) then
            call make_error(err, '&sweep: realizations must be 0 .. ' // itoa(max_realizations) &
                            // ', got ' // itoa(sw%realizations))
            return
         end if
         if (sw%bins < 1 .or. sw%bins > 100000) then
            call make_error(err, '&sweep: bins must be 1 .. 100000, got ' // itoa(sw%bins))
            return
         end if
         call need_choice(err, 'sweep', 'distribution', sw%distribution, &
                          distribution_words)
         if (allocated(err)) return
         if (len_trim(deck%run%checkpoint) > 0) then
            call make_error(err, '&run: checkpoint = ''' // trim(deck%run%checkpoint) // &
                            ''' is not used by --sweep (a sweep''s cases write no files); ' // &
                            'remove it from the sweep deck')
            return
         end if
         if (deck%gauges%n > 0) then
            call make_error(err, '&gauges: not used by --sweep (a sweep''s cases write no ' // &
                            'files); remove it from the sweep deck')
            return
         end if
         if (len_trim(sw%vary) == 0) then
            if (sw%realizations == 0 .and. len_trim(sw%perturb) > 0) then
               call make_error(err, '&sweep: perturb = ''' // trim(sw%perturb) // ''' needs ' &
                               // 'realizations > 0 (the ensemble''s size)')
               return
            else if (sw%realizations == 0) then
               call make_error(err, '&sweep: nothing to sweep: give realizations > 0, or vary ' &
                               // 'and values')
               return
            end if
            if (sw%n_values > 0) then
               call make_error(err, '&sweep: values are given but vary is not')
               return
            end if
         else
            if (sw%n_values == 0) then
               call make_error(err, '&sweep: vary = ''' // trim(sw%vary) // ''' needs values')
               return
            end if
            do k = sw%n_values + 1, max_sweep_values
               if (is_set(sw%values(k))) then
                  call make_error(err, '&sweep: values(' // itoa(k) // ') is given but values(' &
                                  // itoa(sw%n_values + 1) // ') is not')
                  return
               end if
            end do
            do k = 1, sw%n_values
               call need_finite(err, 'sweep', 'values(' // itoa(k) // ')', sw%values(k))
            end do
            if (allocated(err)) return
         end if
         call validate_ensemble(deck, err)
         if (allocated(err)) return
         if (sw%realizations > 0 .and. deck%field%kind /= 'weibull' .and. &
             len_trim(sw%perturb) == 0) then
            call make_error(err, '&sweep: realizations need &strength_field kind = ''weibull'' ' &
                            // '(else every realization is the same run)')
            return
         end if
         ! every value must make a valid deck
         do k = 1, sw%n_values
            trial = deck
            call set_deck_value(trial, sw%vary, sw%values(k), err)
            if (allocated(err)) return
            call validate_deck(trial, err)
            if (allocated(err)) then
               err%message = '&sweep: values(' // itoa(k) // ') = ' // rtoa(sw%values(k)) // &
                             ' for ' // trim(sw%vary) // ': ' // err%message
               return
            end if
         end do
      end associate
   end subroutine validate_sweep

   !> &sweep perturb and ensemble_columns (doc/sweeps.md, "Ensembles"): realization i
   !> perturbs one variable the deck sets (not 0), the only thing a realization changes
   !> (no vary, no Weibull field), by a relative spread in [0, 1); the ensemble's columns
   !> are history columns, each once, of an ensemble (realizations > 0, no vary); the
   !> horizon's share is > 0. spread and horizon_tol are refused where nothing uses them.
   subroutine validate_ensemble(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(column_set_t) :: his
      real(wp) :: base
      integer :: k
      character(len=:), allocatable :: what
      associate (sw => deck%sweep)
         if (len_trim(sw%perturb) > 0) then
            what = '&sweep: perturb = ''' // trim(sw%perturb) // ''''
            if (len_trim(sw%vary) > 0) then
               call make_error(err, what // ' and vary = ''' // trim(sw%vary) // ''': a ' // &
                  'sweep is one ensemble (perturb) or values of a variable (vary), not both')
            else if (sw%realizations == 0) then
               call make_error(err, what // ' needs realizations > 0 (the ensemble''s size)')
            else if (deck%field%kind == 'weibull') then
               call make_error(err, what // ' with &strength_field kind = ''weibull'': a ' // &
                  'realization perturbs a variable or draws a strength field, not both')
            else if (.not. (sw%spread >= 0.0_wp .and. sw%spread < 1.0_wp)) then
               call make_error(err, '&sweep: spread must be in [0, 1), got ' // rtoa(sw%spread))
            end if
            if (allocated(err)) return
            call deck_value(deck, sw%perturb, base, err)
            if (allocated(err)) then
               err%message = replace_word(err%message, 'vary', 'perturb')
               return
            end if
            if (.not. is_set(base)) then
               call make_error(err, what // ' is not set in this deck: nothing to perturb')
            else if (.not. (abs(base) > 0.0_wp)) then
               call make_error(err, what // ' is 0 in this deck: (1 + spread u) x 0 ' // &
                               'perturbs nothing')
            end if
            if (allocated(err)) return
         else if (has_var(deck%scan, 'sweep', 'spread')) then
            call make_error(err, '&sweep: spread is given but perturb is not')
            return
         end if
         if (sw%n_ensemble == 0 .and. .not. has_var(deck%scan, 'sweep', 'ensemble_columns')) then
            if (has_var(deck%scan, 'sweep', 'horizon_tol')) call make_error(err, &
               '&sweep: horizon_tol is given but ensemble_columns is not')
            return
         end if
         do k = sw%n_ensemble + 1, size(sw%ensemble_columns)
            if (len_trim(sw%ensemble_columns(k)) == 0) cycle
            if (k > max_ensemble_columns) then
               call make_error(err, '&sweep: ensemble_columns: at most ' // &
                               itoa(max_ensemble_columns) // ' columns, got more')
            else
               call make_error(err, '&sweep: ensemble_columns(' // itoa(k) // ') is given ' // &
                               'but ensemble_columns(' // itoa(sw%n_ensemble + 1) // ') is not')
            end if
            return
         end do
         if (sw%n_ensemble == 0) then
            call make_error(err, '&sweep: ensemble_columns: give at least one history column')
         else if (sw%n_ensemble > max_ensemble_columns) then
            call make_error(err, '&sweep: ensemble_columns: at most ' // &
                            itoa(max_ensemble_columns) // ' columns, got more')
         else if (sw%realizations == 0) then
            call make_error(err, '&sweep: ensemble_columns need realizations > 0 (the ' // &
                            'ensemble: perturb, or a Weibull &strength_field)')
         else if (len_trim(sw%vary) > 0) then
            call make_error(err, '&sweep: ensemble_columns with vary = ''' // trim(sw%vary) // &
                            ''': a sweep with an ensemble has one value (no vary)')
         else if (.not. (sw%horizon_tol > 0.0_wp)) then
            call make_error(err, '&sweep: horizon_tol must be > 0, got ' // rtoa(sw%horizon_tol))
         end if
         if (allocated(err)) return
         his = history_set()
         do k = 1, sw%n_ensemble
            if (.not. any(his%col%name == sw%ensemble_columns(k))) then
               call make_error(err, '&sweep: ensemble_columns(' // itoa(k) // ') = ''' // &
                  trim(sw%ensemble_columns(k)) // ''' is not a history column (' // &
                  column_list(his) // ')')
            else if (any(sw%ensemble_columns(:k - 1) == sw%ensemble_columns(k))) then
               call make_error(err, '&sweep: ensemble_columns(' // itoa(k) // ') = ''' // &
                  trim(sw%ensemble_columns(k)) // ''' is given twice')
            end if
            if (allocated(err)) return
         end do
      end associate
   contains
      !> The history's column names, ', '-separated.
      pure function column_list(set) result(text)
         type(column_set_t), intent(in) :: set   !! the history's columns
         character(len=:), allocatable :: text
         integer :: j
         text = trim(set%col(1)%name)
         do j = 2, size(set%col)
            text = text // ', ' // trim(set%col(j)%name)
         end do
      end function column_list
      !> text with its first ' old ' ('&sweep: vary = ...') made ' new '.
      pure function replace_word(text, old, new) result(out)
         character(len=*), intent(in) :: text   !! a message
         character(len=*), intent(in) :: old    !! a word of it
         character(len=*), intent(in) :: new    !! what it becomes
         character(len=:), allocatable :: out
         integer :: i
         out = text
         i = index(out, ' ' // old // ' ')
         if (i > 0) out = out(:i) // new // out(i + len(old) + 1:)
      end function replace_word
   end subroutine validate_ensemble

   !> The value the deck holds of a variable a sweep may vary (name as set_deck_value
   !> takes it; unset, the "not given" marker: is_set false).
   subroutine deck_value(deck, name, value, err)
      type(deck_t), intent(in) :: deck     !! the deck
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(out) :: value       !! its value
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      type(deck_t) :: copy
      copy = deck
      call sweep_variable(copy, name, .false., value, err)
   end subroutine deck_value

   !> Set the deck variable a sweep varies: name as in the deck, 'p0' or 'velocity(2)'
   !> (the reals deck_params marks sweep=.true.).
   subroutine set_deck_value(deck, name, value, err)
      type(deck_t), intent(inout) :: deck   !! the deck
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(in) :: value        !! the value to set
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      real(wp) :: x
      x = value
      call sweep_variable(deck, name, .true., x, err)
   end subroutine set_deck_value

   !> Find the deck variable a sweep varies (name as in the deck, 'p0' or 'velocity(2)': the
   !> reals deck_params marks sweep=.true.), and set it to value (set) or read its value.
   subroutine sweep_variable(deck, name, set, value, err)
      type(deck_t), intent(inout) :: deck   !! the deck
      character(len=*), intent(in) :: name   !! variable name
      logical, intent(in) :: set           !! set it (else read it)
      real(wp), intent(inout) :: value     !! the value to set, or the value read
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=:), allocatable :: base
      type(param_pass_t) :: pass
      integer :: j, p, ios
      base = trim(name)
      j = 0
      p = index(base, '(')
      if (p > 0) then
         if (base(len(base):) /= ')') then
            call make_error(err, '&sweep: vary = ''' // base // ''' is not a deck variable')
            return
         end if
         read(base(p + 1:len(base) - 1), *, iostat=ios) j
         if (ios /= 0 .or. j < 1 .or. j > deck%seg%n) then
            call make_error(err, '&sweep: vary = ''' // base // ''': the index must be a ' // &
                            'segment 1 .. ' // itoa(deck%seg%n))
            return
         end if
         base = base(:p - 1)
      end if
      pass = param_pass_t(mode=pass_find, name=base, index=j)
      call deck_params(deck, pass)
      if (pass%indexed .and. j == 0) then
         call make_error(err, '&sweep: vary = ''' // base // ''' needs a segment index, ' // &
                         'e.g. ''' // base // '(1)''')
      else if (.not. pass%indexed .and. j /= 0) then
         call make_error(err, '&sweep: vary = ''' // trim(name) // ''': ' // base // &
                         ' takes no index')
      else if (.not. pass%found) then
         call make_error(err, '&sweep: vary = ''' // trim(name) // ''' is not a variable a ' &
                         // 'sweep can vary (' // pass%sweepable // ')')
      else if (set) then
         pass = param_pass_t(mode=pass_set, name=base, index=j, value=value)
         call deck_params(deck, pass)
      else
         value = pass%value
      end if
   end subroutine sweep_variable

   ! ---------------------------------------------------------------- validation

   !> Check every value; the first violation becomes the error. Fills derived counts.
   subroutine validate_deck(deck, err)
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(out) :: err   !! the error (allocated: it failed)
      call validate_run(deck%run, err)
      if (.not. allocated(err)) call validate_segments(deck%seg, err)
      if (.not. allocated(err)) call validate_mesh(deck%mesh, deck%seg%n, err)
      if (.not. allocated(err)) call validate_ends(deck%ends, err)
      if (.not. allocated(err)) call validate_load(deck%load, deck%ends, err)
      if (.not. allocated(err)) call validate_initial(deck, err)
      if (.not. allocated(err)) call validate_field(deck, err)
      if (.not. allocated(err)) call validate_gauges(deck, err)
      if (.not. allocated(err)) call validate_impactor(deck, err)
   end subroutine validate_deck

   !> &impactor: a mass > 0 striking a free face that no load acts on (the half-mass model:
   !> its exact step needs the face's half node, doc/impactor.md); velocity finite, gap and
   !> cushion >= 0.
   subroutine validate_impactor(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=name_len) :: face_end
      associate (m => deck%impactor)
         if (.not. m%on) return
         call need_choice(err, 'impactor', 'face', m%face, face_words)
         call need_positive(err, 'impactor', 'mass', m%mass)
         call need_finite(err, 'impactor', 'velocity', m%velocity)
         call need_nonnegative(err, 'impactor', 'gap', m%gap)
         call need_nonnegative(err, 'impactor', 'cushion', m%cushion, ' (0: rigid contact)')
         if (allocated(err)) return
         if (m%face == 'top') then
            face_end = deck%ends%top
         else
            face_end = deck%ends%bottom
         end if
         if (face_end /= 'free') then
            call make_error(err, '&impactor: face = ''' // trim(m%face) // ''' is a ''' // &
                            trim(face_end) // ''' end (&ends); the mass strikes a free face')
         else if (deck%load%kind /= 'none' .and. deck%load%face == m%face) then
            call make_error(err, '&impactor: face = ''' // trim(m%face) // ''' is the loaded ' &
                            // 'face (&load face); the mass strikes a face no load acts on')
         else if (deck%run%model == 'full-mass') then
            call make_error(err, '&impactor: the striking mass needs &run model = ' // &
                            '''half-mass'' (its exact step rests on the face''s half node)')
         end if
      end associate
   end subroutine validate_impactor

   !> &gauges: positions given in order x(1), x(2), ... (at most max_gauges), each finite and
   !> within the bar [0, sum of the segment lengths] (to the round-off of that sum); every
   !> >= 1, &run history_every when not given.
   subroutine validate_gauges(deck, err)
      type(deck_t), intent(inout) :: deck   !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: k
      real(wp) :: total   ! the bar's length [m]
      associate (g => deck%gauges)
         g%n = 0
         do k = 1, size(g%x)
            if (.not. is_set(g%x(k))) exit
            g%n = k
         end do
         if (g%n == 0 .and. .not. has_group(deck%scan, 'gauges')) return
         if (g%n == 0 .and. any(is_set(g%x))) then
            ! positions given, but not from x(1) on: name the first one given
            k = findloc(is_set(g%x), .true., dim=1)
            if (k > max_gauges) then
               call make_error(err, '&gauges: x(' // itoa(k) // '): at most ' // &
                               itoa(max_gauges) // ' gauges')
            else
               call make_error(err, '&gauges: x(' // itoa(k) // ') is given but x(1) is not: ' // &
                               'give the positions in order from x(1)')
            end if
         else if (g%n == 0) then
            call make_error(err, '&gauges: x is required (the positions of the gauges, m)')
         else if (g%n > max_gauges) then
            call make_error(err, '&gauges: x: at most ' // itoa(max_gauges) // &
                            ' gauges, got more')
         end if
         do k = g%n + 1, size(g%x)
            if (allocated(err)) return
            if (is_set(g%x(k))) call make_error(err, '&gauges: x(' // itoa(k) // &
               ') is given but x(' // itoa(g%n + 1) // ') is not')
         end do
         total = sum(deck%seg%length(1:deck%seg%n))
         do k = 1, g%n
            call need_finite(err, 'gauges', 'x(' // itoa(k) // ')', g%x(k))
            if (allocated(err)) return
            if (g%x(k) < 0.0_wp .or. g%x(k) > total * (1.0_wp + 1.0e-12_wp)) then
               call make_error(err, '&gauges: x(' // itoa(k) // ') = ' // rtoa(g%x(k)) // &
                  ' m is outside the bar [0, ' // rtoa(total) // '] m')
               return
            end if
         end do
         if (g%every == 0 .and. .not. has_var(deck%scan, 'gauges', 'every')) then
            g%every = deck%run%history_every
         end if
         if (g%every < 1) call make_error(err, '&gauges: every must be >= 1, got ' // &
                                          itoa(g%every))
         call validate_sides(g, err)
      end associate
   end subroutine validate_gauges

   !> &gauges side: given in order from side(1), one value for all gauges or one per gauge,
   !> each 'above' or 'below'; not given: 'above' for all (doc/gauges.md).
   subroutine validate_sides(g, err)
      type(gauges_cfg), intent(inout) :: g   !! &gauges values (n set)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: k
      if (allocated(err)) return
      g%n_side = 0
      do k = 1, size(g%side)
         if (len_trim(g%side(k)) > 0) g%n_side = k
      end do
      do k = 1, g%n_side
         if (len_trim(g%side(k)) == 0) then
            call make_error(err, '&gauges: side(' // itoa(g%n_side) // ') is given but side(' &
                            // itoa(k) // ') is not: give one side for all gauges or one per gauge')
            return
         end if
         call need_choice(err, 'gauges', 'side(' // itoa(k) // ')', g%side(k), side_words)
         if (allocated(err)) return
      end do
      if (g%n_side == 0) then
         g%side(1) = side_words(1)
         g%n_side = 1
      else if (g%n_side /= 1 .and. g%n_side /= g%n) then
         call make_error(err, '&gauges: side: give one value for all gauges or one per ' // &
                         'gauge (' // itoa(g%n) // '), got ' // itoa(g%n_side))
      end if
   end subroutine validate_sides

   !> Error unless x is a finite number; name is the variable as the user writes it.
   subroutine need_finite(err, group, name, x)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(in) :: x               !! the value
      if (allocated(err)) return
      if (.not. ieee_is_finite(x)) call make_error(err, '&' // group // ': ' // name // &
         ' must be a finite number, got ' // rtoa(x))
   end subroutine need_finite

   !> Error unless x was given, is finite and > 0 (or >= 0 when zero_ok).
   subroutine need_positive(err, group, name, x, zero_ok)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(in) :: x               !! the value
      logical, intent(in), optional :: zero_ok   !! accept 0 too (default: no)
      logical :: zok
      if (allocated(err)) return
      zok = .false.
      if (present(zero_ok)) zok = zero_ok
      if (.not. is_set(x)) then
         call make_error(err, '&' // group // ': ' // name // ' is required')
         return
      end if
      call need_finite(err, group, name, x)
      if (allocated(err)) return
      if (zok) then
         if (x < 0.0_wp) call make_error(err, '&' // group // ': ' // name // &
            ' must be >= 0, got ' // rtoa(x))
      else
         if (x <= 0.0_wp) call make_error(err, '&' // group // ': ' // name // &
            ' must be > 0, got ' // rtoa(x))
      end if
   end subroutine need_positive

   !> Error unless x is finite and >= 0; note follows "must be >= 0" in the message.
   subroutine need_nonnegative(err, group, name, x, note)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: name   !! variable name
      real(wp), intent(in) :: x               !! the value
      character(len=*), intent(in), optional :: note   !! what 0 means, e.g. ' (0: off)'
      call need_finite(err, group, name, x)
      if (allocated(err)) return
      if (x >= 0.0_wp) return
      if (present(note)) then
         call make_error(err, '&' // group // ': ' // name // ' must be >= 0' // note // &
                         ', got ' // rtoa(x))
      else
         call make_error(err, '&' // group // ': ' // name // ' must be >= 0, got ' // rtoa(x))
      end if
   end subroutine need_nonnegative

   !> Error unless value is one of choices.
   subroutine need_choice(err, group, name, value, choices)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=*), intent(in) :: group   !! group name
      character(len=*), intent(in) :: name   !! variable name
      character(len=*), intent(in) :: value   !! its value text
      character(len=*), intent(in) :: choices(:)   !! the values allowed
      character(len=:), allocatable :: list
      integer :: k
      if (allocated(err)) return
      if (any(choices == value)) return
      list = ''
      do k = 1, size(choices)
         if (k > 1) list = list // ' | '
         list = list // '''' // trim(choices(k)) // ''''
      end do
      call make_error(err, '&' // group // ': ' // name // ' must be ' // list // ', got ''' &
                      // trim(value) // '''')
   end subroutine need_choice


   !> Check &run's values.
   subroutine validate_run(run, err)
      type(run_cfg), intent(inout) :: run   !! &run values
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: k
      call need_positive(err, 'run', 't_end', run%t_end)
      call need_finite(err, 'run', 'gravity', run%gravity)
      call need_choice(err, 'run', 'timing', run%timing, timing_words)
      call need_choice(err, 'run', 'shift', run%shift, shift_words)
      call need_choice(err, 'run', 'events', run%events, events_words)
      call need_choice(err, 'run', 'model', run%model, model_words)
      call need_choice(err, 'run', 'header', run%header, header_words)
      if (allocated(err)) return
      ! the paper's rules shift fragments (its (5.2)); moving only the faces is ours
      if (run%shift == 'face' .and. run%events == 'paper') then
         call make_error(err, '&run: shift = ''face'' needs events = ''admissible'' (the paper''s ' &
                         // 'rules shift fragments)')
         return
      end if
      ! the paper's rules put a collision at t^n or t^{n+1}; keeping the overlap as strain is ours
      if (run%timing == 'within' .and. run%events == 'paper') then
         call make_error(err, '&run: timing = ''within'' needs events = ''admissible'' (the ' &
                         // 'paper''s rules join at t^n or t^{n+1})')
         return
      end if
      call need_finite(err, 'run', 'eps_rel', run%eps_rel)
      if (allocated(err)) return
      if (run%eps_rel < 0.0_wp .or. run%eps_rel > 1.0e-3_wp) then
         call make_error(err, '&run: eps_rel must be in [0, 1e-3], got ' // rtoa(run%eps_rel))
         return
      end if
      call need_nonnegative(err, 'run', 'energy_guard', run%energy_guard, ' (0: off)')
      if (allocated(err)) return
      if (run%history_every < 1) then
         call make_error(err, '&run: history_every must be >= 1, got ' // itoa(run%history_every))
         return
      end if
      if (run%field_every < 0) then
         call make_error(err, '&run: field_every must be >= 0 (0: no x-t fields), got ' // &
                         itoa(run%field_every))
         return
      end if
      if (run%checkpoint_every < 0) then
         call make_error(err, '&run: checkpoint_every must be >= 0 (0: at t_end only), got ' // &
                         itoa(run%checkpoint_every))
         return
      end if
      if (run%checkpoint_every > 0 .and. len_trim(run%checkpoint) == 0) then
         call make_error(err, '&run: checkpoint_every = ' // itoa(run%checkpoint_every) // &
                         ' needs checkpoint = ''file.h5'' (the restart file to write)')
         return
      end if
      if (run%field_every > 0 .and. .not. run%hdf5) then
         call make_error(err, '&run: field_every = ' // itoa(run%field_every) // &
                         ' needs hdf5 = .true. (the x-t fields are written to PREFIX.h5 only)')
         return
      end if
      run%n_profiles = 0
      do k = 1, max_profiles
         if (.not. is_set(run%profile_times(k))) exit
         run%n_profiles = k
      end do
      do k = 1, max_profiles
         ! (a time beyond the first one not given is only looked at: the loop runs over
         ! every slot of every sweep case)
         if (k > run%n_profiles) then
            if (is_set(run%profile_times(k))) call make_error(err, '&run: profile_times(' // &
               itoa(k) // ') is given but profile_times(' // itoa(run%n_profiles + 1) // &
               ') is not')
            if (allocated(err)) return
            cycle
         end if
         associate (name => 'profile_times(' // itoa(k) // ')')
            call need_positive(err, 'run', name, run%profile_times(k), zero_ok=.true.)
            if (allocated(err)) return
            if (run%profile_times(k) > run%t_end) call make_error(err, '&run: ' // name // &
               ' = ' // rtoa(run%profile_times(k)) // ' is after t_end = ' // rtoa(run%t_end))
            if (k > 1 .and. .not. allocated(err)) call need_order(k)
         end associate
         if (allocated(err)) return
      end do
   contains
      !> profile_times must not decrease: check entry k against entry k - 1.
      subroutine need_order(k)
         integer, intent(in) :: k   !! index into profile_times (> 1)
         if (run%profile_times(k) < run%profile_times(k - 1)) call make_error(err, &
            '&run: profile_times(' // itoa(k) // ') must not be earlier than profile_times(' &
            // itoa(k - 1) // ')')
      end subroutine need_order
   end subroutine validate_run

   !> Check &mesh's values.
   subroutine validate_mesh(mesh, nseg, err)
      type(mesh_cfg), intent(in) :: mesh   !! &mesh values
      integer, intent(in) :: nseg          !! segments (&segments n)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      if (allocated(err)) return
      call need_finite(err, 'mesh', 'dt', mesh%dt)
      if (allocated(err)) return
      if (mesh%dt < 0.0_wp) then
         call make_error(err, '&mesh: dt must be >= 0 (0: set by cells), got ' // rtoa(mesh%dt))
      else if (mesh%cells < 0) then
         call make_error(err, '&mesh: cells must be >= 0, got ' // itoa(mesh%cells))
      else if (mesh%dt > 0.0_wp .and. mesh%cells > 0) then
         call make_error(err, '&mesh: cells: give either cells or dt, not both')
      else if (mesh%dt <= 0.0_wp .and. mesh%cells == 0) then
         call make_error(err, '&mesh: cells is required (cells in segment ref_segment), or give dt > 0')
      else if (mesh%ref_segment < 1 .or. mesh%ref_segment > nseg) then
         call make_error(err, '&mesh: ref_segment must be in 1..' // itoa(nseg) // ', got ' // &
                         itoa(mesh%ref_segment))
      end if
      call need_choice(err, 'mesh', 'fit', mesh%fit, fit_words)
   end subroutine validate_mesh

   !> Check &segments' values and fill the defaults of the segments given.
   subroutine validate_segments(seg, err)
      type(segments_cfg), intent(inout) :: seg   !! &segments values (defaults filled in)
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: j
      character(len=:), allocatable :: sj
      if (allocated(err)) return
      if (seg%n < 1 .or. seg%n > max_segments) then
         call make_error(err, '&segments: n must be in 1..' // itoa(max_segments) // ', got ' &
                         // itoa(seg%n))
         return
      end if
      do j = 1, max_segments
         if (j <= seg%n) then
            ! (the suffix is formatted where it is read: beyond n, only in an error)
            sj = '(' // itoa(j) // ')'
            call need_positive(err, 'segments', 'length' // sj, seg%length(j))
            call need_positive(err, 'segments', 'young' // sj, seg%young(j))
            call need_positive(err, 'segments', 'density' // sj, seg%density(j))
            if (is_set(seg%strength(j))) then
               call need_finite(err, 'segments', 'strength' // sj, seg%strength(j))
            else
               seg%strength(j) = -1.0_wp
            end if
            call breaking_extra('fracture_energy', seg%fracture_energy(j), 'opens no crack')
            call breaking_extra('damage_integral', seg%damage_integral(j), 'does not break')
            if (is_set(seg%damage_exponent(j))) then
               call need_positive(err, 'segments', 'damage_exponent' // sj, &
                                  seg%damage_exponent(j))
            else
               seg%damage_exponent(j) = 2.0_wp
            end if
            if (is_set(seg%velocity(j))) then
               call need_finite(err, 'segments', 'velocity' // sj, seg%velocity(j))
            else
               seg%velocity(j) = 0.0_wp
            end if
            if (is_set(seg%area(j))) then
               call need_positive(err, 'segments', 'area' // sj, seg%area(j))
            else
               seg%area(j) = 1.0_wp
            end if
            if (j < seg%n) then
               if (len_trim(seg%interface(j)) == 0) seg%interface(j) = 'bonded'
               call need_choice(err, 'segments', 'interface' // sj, seg%interface(j), &
                                interface_words)
               if (is_set(seg%gap(j))) then
                  call need_positive(err, 'segments', 'gap' // sj, seg%gap(j), zero_ok=.true.)
                  if (.not. allocated(err) .and. seg%gap(j) > 0.0_wp .and. &
                      seg%interface(j) /= 'dry') call make_error(err, '&segments: gap' // sj // &
                      ' > 0 needs interface' // sj // ' = ''dry''')
               else
                  seg%gap(j) = 0.0_wp
               end if
            else
               if (len_trim(seg%interface(j)) > 0) call make_error(err, '&segments: interface' // &
                  sj // ' is given but there are only ' // itoa(seg%n - 1) // ' interfaces (n = ' &
                  // itoa(seg%n) // ')')
               if (is_set(seg%gap(j)) .and. .not. allocated(err)) call make_error(err, &
                  '&segments: gap' // sj // ' is given but there are only ' // itoa(seg%n - 1) &
                  // ' interfaces (n = ' // itoa(seg%n) // ')')
            end if
         else
            call beyond_n('length', seg%length(j))
            call beyond_n('young', seg%young(j))
            call beyond_n('density', seg%density(j))
            call beyond_n('strength', seg%strength(j))
            call beyond_n('fracture_energy', seg%fracture_energy(j))
            call beyond_n('damage_integral', seg%damage_integral(j))
            call beyond_n('damage_exponent', seg%damage_exponent(j))
            call beyond_n('velocity', seg%velocity(j))
            call beyond_n('area', seg%area(j))
            if (j >= seg%n) call beyond_n('gap', seg%gap(j))
            if (len_trim(seg%interface(j)) > 0 .and. .not. allocated(err)) then
               call make_error(err, '&segments: interface(' // itoa(j) // ') is given but n = ' &
                               // itoa(seg%n))
            end if
         end if
         if (allocated(err)) return
      end do
      call need_impedance_ratio(seg, err)
   contains
      !> A real of segment j that only a breakable segment uses (default 0): >= 0, and > 0
      !> only where strength(j) >= 0; note says what an unbreakable segment does not do.
      subroutine breaking_extra(name, x, note)
         character(len=*), intent(in) :: name   !! variable name
         real(wp), intent(inout) :: x   !! its value for the segment (default set)
         character(len=*), intent(in) :: note   !! why an unbreakable segment needs none
         if (.not. is_set(x)) then
            x = 0.0_wp
            return
         end if
         call need_positive(err, 'segments', name // sj, x, zero_ok=.true.)
         if (.not. allocated(err) .and. x > 0.0_wp .and. .not. seg%strength(j) >= 0.0_wp) then
            call make_error(err, '&segments: ' // name // sj // ' > 0 needs strength' // sj // &
                            ' >= 0 (an unbreakable segment ' // note // ')')
         end if
      end subroutine breaking_extra

      !> A value given for a segment beyond n is an error.
      subroutine beyond_n(name, x)
         character(len=*), intent(in) :: name   !! variable name
         real(wp), intent(in) :: x   !! its value for the segment
         if (allocated(err)) return
         if (is_set(x)) call make_error(err, '&segments: ' // name // '(' // itoa(j) // &
                                        ') is given but n = ' // itoa(seg%n) // &
                                        ' (set n to the number of segments)')
      end subroutine beyond_n
   end subroutine validate_segments

   !> The axial impedances rho a A = sqrt(young density) area of the segments may differ by
   !> at most max_impedance_ratio (compared in logarithms: no product can overflow). The
   !> error names area(j) of the segment with the smallest one, or its young and density
   !> where the two segments' areas are the same.
   subroutine need_impedance_ratio(seg, err)
      type(segments_cfg), intent(in) :: seg   !! &segments values, validated
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      real(wp) :: lz(seg%n)
      integer :: lo, hi
      character(len=:), allocatable :: what, slo
      if (allocated(err)) return
      lz = 0.5_wp * (log(seg%young(1:seg%n)) + log(seg%density(1:seg%n))) + &
           log(seg%area(1:seg%n))
      lo = minloc(lz, dim=1)
      hi = maxloc(lz, dim=1)
      if (lz(hi) - lz(lo) <= log(max_impedance_ratio)) return
      slo = '(' // itoa(lo) // ')'
      what = 'area' // slo
      if (seg%area(lo) == seg%area(hi)) what = 'young' // slo // ', density' // slo
      call make_error(err, '&segments: ' // what // ': the axial impedance rho a A of segment ' &
         // itoa(hi) // ' is ' // power_text(lz(hi) - lz(lo), 3) // ' times that of segment ' // &
         itoa(lo) // '; at most ' // power_text(log(max_impedance_ratio)) // ' is supported ' &
         // '(beyond, segment ' // itoa(lo) // '''s wave energy is lost in the round-off of ' &
         // 'segment ' // itoa(hi) // '''s; doc/areas.md)')
   end subroutine need_impedance_ratio

   !> Check &ends' values.
   subroutine validate_ends(ends, err)
      type(ends_cfg), intent(in) :: ends   !! &ends values
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      call need_choice(err, 'ends', 'top', ends%top, top_words)
      call need_choice(err, 'ends', 'bottom', ends%bottom, bottom_words)
      call need_finite(err, 'ends', 'base_gap', ends%base_gap)
      call need_finite(err, 'ends', 'base_gap_top', ends%base_gap_top)
      if (allocated(err)) return
      if (ends%base_gap < 0.0_wp) then
         call make_error(err, '&ends: base_gap must be >= 0, got ' // rtoa(ends%base_gap))
      else if (ends%base_gap > 0.0_wp .and. ends%bottom /= 'base') then
         call make_error(err, '&ends: base_gap is given but bottom = ''' // trim(ends%bottom) // '''')
      else if (ends%base_gap_top < 0.0_wp) then
         call make_error(err, '&ends: base_gap_top must be >= 0, got ' // rtoa(ends%base_gap_top))
      else if (ends%base_gap_top > 0.0_wp .and. ends%top /= 'base') then
         call make_error(err, '&ends: base_gap_top is given but top = ''' // trim(ends%top) // '''')
      end if
   end subroutine validate_ends

   !> Check &load's values against the ends.
   subroutine validate_load(load, ends, err)
      type(load_cfg), intent(in) :: load   !! &load values
      type(ends_cfg), intent(in) :: ends   !! &ends values
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      character(len=name_len) :: face_end
      call need_choice(err, 'load', 'kind', load%kind, kind_words)
      call need_choice(err, 'load', 'face', load%face, face_words)
      if (allocated(err) .or. load%kind == 'none') return
      if (load%face == 'top') then
         face_end = ends%top
      else
         face_end = ends%bottom
      end if
      if (face_end /= 'free' .and. face_end /= 'transmit') then
         call make_error(err, '&load: face = ''' // trim(load%face) // ''' is a ''' // &
                         trim(face_end) // ''' end (&ends); a load acts on a free face ' // &
                         '(or enters as an incident wave through a transmitting one)')
         return
      end if
      if ((load%kind == 'power' .or. load%kind == 'exponential') .and. .not. is_set(load%p0)) then
         call make_error(err, '&load: p0 is required for kind = ''' // trim(load%kind) // '''')
         return
      end if
      if (load%kind == 'power') then
         call need_finite(err, 'load', 'p0', load%p0)
         call need_nonnegative(err, 'load', 'exponent', load%exponent)
         if (allocated(err)) return
         if (is_set(load%t_k)) then
            call need_positive(err, 'load', 't_k', load%t_k)
         else if (load%exponent > 0.0_wp) then
            call make_error(err, '&load: t_k is required when exponent > 0')
         end if
         if (allocated(err)) return
         if (is_set(load%t_cut)) then
            call need_positive(err, 'load', 't_cut', load%t_cut)
            if (allocated(err)) return
            if (is_set(load%t_k)) then
               if (load%t_cut > load%t_k) call make_error(err, '&load: t_cut = ' // &
                  rtoa(load%t_cut) // ' is after t_k = ' // rtoa(load%t_k) // &
                  ' (p = p0 (1 - t/t_k)**exponent is defined up to t_k)')
            end if
         end if
      else if (load%kind == 'exponential') then
         call need_finite(err, 'load', 'p0', load%p0)
         if (.not. is_set(load%t_k) .and. .not. allocated(err)) then
            call make_error(err, '&load: t_k (decay time) is required for kind = ''exponential''')
            return
         end if
         call need_positive(err, 'load', 't_k', load%t_k)
         if (is_set(load%t_cut)) call need_positive(err, 'load', 't_cut', load%t_cut)
      else if (load%kind == 'table') then
         if (len_trim(load%table) == 0) call make_error(err, &
            '&load: table (file of two columns t p) is required for kind = ''table''')
      end if
   end subroutine validate_load

   !> &strength_field: a Weibull field needs its modulus and scale and a breakable segment
   !> (it replaces the strength of the segments whose strength is >= 0).
   subroutine validate_field(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      call need_choice(err, 'strength_field', 'kind', deck%field%kind, field_words)
      if (allocated(err) .or. deck%field%kind /= 'weibull') return
      call need_positive(err, 'strength_field', 'modulus', deck%field%modulus)
      call need_positive(err, 'strength_field', 'scale', deck%field%scale)
      if (allocated(err)) return
      call need_weibull_range(deck%field%modulus, deck%field%scale, err)
      if (allocated(err)) return
      if (.not. any(deck%seg%strength(1:deck%seg%n) >= 0.0_wp)) call make_error(err, &
         '&strength_field: kind = ''weibull'' applies to segments with strength >= 0 ' // &
         '(&segments strength), and there is none')
   end subroutine validate_field

   !> Every strength a Weibull field can draw, scale (-ln(1 - u))^(1/modulus) for the
   !> generator's u (spb_random: weibull_log_min .. weibull_log_max), must lie in the deck's
   !> range (at most huge_real) and be a normal number (not below tiny(1.0_wp)): checked in
   !> logarithms before any is drawn, so a small modulus cannot overflow the field.
   subroutine need_weibull_range(modulus, scale, err)
      real(wp), intent(in) :: modulus      !! Weibull modulus, > 0 [-]
      real(wp), intent(in) :: scale        !! Weibull scale, > 0 [Pa]
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      real(wp) :: ln_hi, ln_lo
      character(len=:), allocatable :: what
      ln_hi = log(scale) + log(weibull_log_max) / modulus
      ln_lo = log(scale) + log(weibull_log_min) / modulus
      if (.not. (ln_hi > log(huge_real) .or. ln_lo < log(tiny(1.0_wp)))) return
      what = '&strength_field: modulus = ' // rtoa(modulus) // ' with scale = ' // &
             rtoa(scale) // ' draws strengths '
      if (ln_hi > log(huge_real)) then
         call make_error(err, what // 'up to ' // power_text(ln_hi) // ' Pa (overflow: at ' // &
            'most ' // rtoa(huge_real) // ' Pa); give a larger modulus or a smaller scale')
      else if (ln_lo < log(tiny(1.0_wp))) then
         call make_error(err, what // 'down to ' // power_text(ln_lo) // ' Pa (underflow: ' // &
            'at least ' // power_text(log(tiny(1.0_wp))) // ' Pa); give a larger modulus ' // &
            'or a larger scale')
      end if
   end subroutine need_weibull_range

   !> exp(ln_x) written as a power of ten ('3e1352'), for a logarithm beyond the reals; with
   !> digits, to that many significant digits, trailing zeros dropped ('1.01e6', '1e30').
   function power_text(ln_x, digits) result(text)
      real(wp), intent(in) :: ln_x         !! natural logarithm of the number
      integer, intent(in), optional :: digits   !! significant digits (default 1)
      character(len=:), allocatable :: text
      character(len=:), allocatable :: frac
      real(wp) :: e10
      integer :: m, e, d, unit
      e10 = ln_x / log(10.0_wp)
      if (abs(e10) > 1.0e9_wp) then
         text = '10^' // rtoa(e10)
         return
      end if
      d = 1
      if (present(digits)) d = digits
      unit = 10**(d - 1)
      e = floor(e10)
      m = nint(real(unit, wp) * 10.0_wp**(e10 - real(e, wp)))
      if (m >= 10 * unit) then
         m = unit
         e = e + 1
      end if
      text = itoa(m / unit)
      if (mod(m, unit) /= 0) then
         ! the digits after the point, leading zeros kept, trailing ones dropped
         frac = itoa(unit + mod(m, unit))
         frac = frac(2:)
         do while (frac(len(frac):) == '0')
            frac = frac(:len(frac) - 1)
         end do
         text = text // '.' // frac
      end if
      text = text // 'e' // itoa(e)
   end function power_text

   !> Check &initial's values.
   subroutine validate_initial(deck, err)
      type(deck_t), intent(in) :: deck     !! the deck
      type(spb_error_t), allocatable, intent(inout) :: err   !! the error (allocated: it failed)
      integer :: j
      if (deck%run%model == 'full-mass' .and. any(deck%seg%interface(1:deck%seg%n - 1) == 'dry')) then
         call make_error(err, '&segments: interface = ''dry'' needs &run model = ''half-mass'' ' &
                         // '(the full-mass model breaks springs, not nodes)')
         return
      end if
      if (deck%run%model == 'full-mass' .and. any(deck%seg%fracture_energy(1:deck%seg%n) > 0.0_wp)) then
         call make_error(err, '&segments: fracture_energy > 0 needs &run model = ''half-mass'' ' &
                         // '(cohesive cracks open at nodes; the full-mass model breaks springs)')
         return
      end if
      if (deck%run%model == 'full-mass' .and. &
          any(deck%seg%damage_integral(1:deck%seg%n) > 0.0_wp)) then
         call make_error(err, '&segments: damage_integral > 0 needs &run model = ''half-mass'' ' &
                         // '(sections break at nodes; the full-mass model breaks springs)')
         return
      end if
      ! a cohesive crack opens at its strength: with none (and no strength field to draw one)
      ! the section could only break brittle, which would leave Gc unused without a word
      do j = 1, deck%seg%n
         if (deck%seg%fracture_energy(j) > 0.0_wp .and. .not. deck%seg%strength(j) > 0.0_wp &
             .and. deck%field%kind /= 'weibull') then
            call make_error(err, '&segments: fracture_energy(' // itoa(j) // ') > 0 needs ' // &
               'strength(' // itoa(j) // ') > 0 (a cohesive crack opens at the strength), or ' // &
               'a &strength_field')
            return
         end if
      end do
      call need_choice(err, 'initial', 'state', deck%init%state, state_words)
      call need_finite(err, 'initial', 'strain_rate', deck%init%strain_rate)
      if (allocated(err)) return
      if (abs(deck%init%strain_rate) > 0.0_wp .and. (deck%ends%top == 'fixed' .or. &
          deck%ends%bottom == 'fixed' .or. deck%ends%bottom == 'base' .or. &
          deck%ends%top == 'base')) then
         call make_error(err, '&initial: strain_rate = ' // rtoa(deck%init%strain_rate) // &
            ' needs ends that let the bar stretch about its centre of mass (&ends top, ' // &
            'bottom = ''free'', ''transmit'' or ''velocity'')')
         return
      end if
      if (deck%init%state == 'static' .and. abs(deck%run%gravity) > 0.0_wp) then
         if (any(deck%seg%gap(1:deck%seg%n - 1) > 0.0_wp)) then
            call make_error(err, '&initial: state = ''static'' with a gap in &segments gap: ' &
                            // 'separated pieces are not in equilibrium')
            return
         end if
         ! a base holds the bar's weight only where gravity presses the bar onto it
         if ((deck%ends%bottom == 'base' .and. deck%run%gravity < 0.0_wp) .or. &
             (deck%ends%top == 'base' .and. deck%run%gravity > 0.0_wp)) then
            call make_error(err, '&initial: state = ''static'' with gravity = ' // &
               rtoa(deck%run%gravity) // ' pulls the bar away from its base (&ends ' // &
               trim(merge('bottom', 'top   ', deck%ends%bottom == 'base' .and. &
               deck%run%gravity < 0.0_wp)) // ' = ''base''), which cannot hold it by a pull')
            return
         end if
         if (deck%ends%top == 'base' .and. deck%ends%base_gap_top > 0.0_wp) then
            call make_error(err, '&initial: state = ''static'' with &ends base_gap_top > 0: a ' &
                            // 'bar off the base is not in equilibrium')
            return
         end if
         if (deck%ends%bottom == 'base' .and. deck%ends%base_gap > 0.0_wp) then
            call make_error(err, '&initial: state = ''static'' with &ends base_gap > 0: a bar ' &
                            // 'above the base is not in equilibrium')
            return
         end if
         if (deck%ends%top == 'free' .and. deck%ends%bottom == 'free') call make_error(err, &
            '&initial: state = ''static'' with gravity needs a supported end (&ends top or ' &
            // 'bottom = ''fixed'', ''transmit'', ''velocity'' or ''base''); both ends are free')
      end if
   end subroutine validate_initial

   ! ---------------------------------------------------------------------- echo

   !> Every deck value, defaults included, in echo order: group, name, value as namelist
   !> text, unit, and whether the deck gave it.
   subroutine deck_items(deck, items)
      type(deck_t), intent(in) :: deck     !! the deck
      type(echo_item_t), allocatable, intent(out) :: items(:)   !! the deck values as echoed
      type(deck_t) :: copy
      type(param_pass_t) :: pass
      integer :: k
      copy = deck      ! the echo pass leaves its deck as it is; deck_params takes it inout
      pass%mode = pass_echo
      call deck_params(copy, pass)
      call move_alloc(pass%items, items)
      do k = 1, size(items)
         items(k)%given = has_var(deck%scan, items(k)%group, items(k)%name)
      end do
   end subroutine deck_items

   !> A mesh fault (spb_mesh) in the deck's terms: the one-line message of the bad input.
   function mesh_fault_message(fault, prob) result(msg)
      type(mesh_fault_t), intent(in) :: fault   !! why no mesh (fault_none: built)
      type(problem_t), intent(in) :: prob   !! the problem
      character(len=:), allocatable :: msg
      character(len=:), allocatable :: sj
      sj = itoa(fault%segment)
      select case (fault%kind)
      case (fault_cells)
         msg = '&mesh: cells = ' // itoa(prob%cells) // '; the limit is ' // itoa(max_cells)
      case (fault_segment_cells)
         msg = '&segments: length(' // sj // ') would need ' // rtoa(fault%cells) // &
               ' cells; the limit is ' // itoa(max_cells)
      case (fault_not_whole)
         msg = '&segments: length(' // sj // ') = ' // rtoa(prob%length(fault%segment)) // &
               ' m is ' // rtoa(fault%cells) // ' cells of dx = a dt = ' // rtoa(fault%dx) // &
               ' m, not a whole number (&mesh fit = ''strict''; use fit = ''stretch'' or ' // &
               'change the length)'
      case (fault_short_segment)
         msg = '&segments: length(' // sj // ') = ' // rtoa(prob%length(fault%segment)) // &
               ' m is less than half a cell of dx = a dt = ' // rtoa(fault%dx) // &
               ' m (&mesh fit = ''stretch'' would make it a whole cell; use a smaller dt or ' // &
               'more cells)'
      case (fault_mesh_cells)
         msg = '&mesh: cells: the mesh would have ' // rtoa(fault%cells) // &
               ' cells; the limit is ' // itoa(max_cells)
      case (fault_short_run)
         msg = '&run: t_end = ' // rtoa(prob%t_end) // ' s is shorter than half a step of ' // &
               'dt = ' // rtoa(fault%dt) // ' s'
      case (fault_long_run)
         msg = '&run: t_end = ' // rtoa(prob%t_end) // ' s needs ' // rtoa(fault%steps) // &
               ' steps of dt = ' // rtoa(fault%dt) // ' s; the limit is ' // itoa(max_steps)
      case default
         msg = ''
      end select
      ! every refusal of the mesh follows from dx = a dt: a wave speed no solid has (a unit
      ! slip in young or density) is the likely cause, and the one line says so
      if (len(msg) > 0) msg = msg // speed_hint(prob)
   contains
      !> '' or, where a segment's wave speed is outside the solids' 20..20000 m/s, a hint at
      !> a unit slip in its young or density (young = 30 meant in GPa makes dt huge).
      function speed_hint(prob) result(hint)
         type(problem_t), intent(in) :: prob   !! the problem
         character(len=:), allocatable :: hint
         real(wp) :: a
         integer :: j
         hint = ''
         do j = 1, prob%nseg
            a = sqrt(prob%young(j) / prob%density(j))
            if (a < 20.0_wp .or. a > 20000.0_wp) then
               hint = ' (young(' // itoa(j) // ') and density(' // itoa(j) // ') give a wave ' &
                      // 'speed of ' // rtoa(a) // ' m/s, outside the solids'' 20..20000 m/s: ' &
                      // 'Pa and kg/m^3 meant?)'
               return
            end if
         end do
      end function speed_hint
   end function mesh_fault_message

   !> The record of a validated deck for the outputs and checkpoints. echo = .false. (a run
   !> that writes no files: a sweep's case) leaves the echo's items out (none), the most of
   !> the record's cost.
   function deck_record(deck, echo) result(rec)
      type(deck_t), intent(in) :: deck     !! the deck
      logical, intent(in), optional :: echo   !! with the echo's items (default .true.)
      type(deck_record_t) :: rec
      integer :: k
      logical :: with_echo
      with_echo = .true.
      if (present(echo)) with_echo = echo
      rec%path = trim(deck%path)
      rec%title = trim(deck%run%title)
      rec%table = deck_file(deck, deck%load%table)
      if (with_echo) then
         call deck_items(deck, rec%items)
      else
         allocate(rec%items(0))
      end if
      rec%hdf5 = deck%run%hdf5
      rec%names_first = deck%run%header == 'names'
      rec%field_every = deck%run%field_every
      rec%t_end = deck%run%t_end
      allocate(rec%profile_times(deck%run%n_profiles))
      rec%profile_times(:) = deck%run%profile_times(1:deck%run%n_profiles)
      allocate(rec%gauge_x(deck%gauges%n))
      rec%gauge_x(:) = deck%gauges%x(1:deck%gauges%n)
      rec%gauge_every = max(deck%gauges%every, 1)
      allocate(rec%gauge_below(deck%gauges%n))
      do k = 1, deck%gauges%n
         rec%gauge_below(k) = deck%gauges%side(min(k, max(deck%gauges%n_side, 1))) == 'below'
      end do
   end function deck_record

   !> Every deck variable (spallbar --deck-help): group by group, its default as the echo
   !> shows it, its unit, what it means and, for a keyword, the values it accepts.
   subroutine write_deck_help(u)
      integer, intent(in) :: u   !! open formatted unit
      type(deck_t) :: defaults
      type(param_pass_t) :: pass
      character(len=:), allocatable :: unit
      integer :: k
      pass%mode = pass_doc
      call deck_params(defaults, pass)
      write(u, '(a)') 'Deck variables: name = default [unit] meaning (doc/deck.md has the ' // &
         'rules that relate them)'
      do k = 1, size(pass%items)
         associate (it => pass%items(k))
            if (k == 1) then
               write(u, '(a)') '&' // it%group
            else if (it%group /= pass%items(k - 1)%group) then
               write(u, '(a)') '/'
               write(u, '(a)') '&' // it%group
            end if
            unit = ''
            if (len(it%unit) > 0) unit = '[' // it%unit // ']'
            write(u, '(a)') '   ' // pad(it%name, 16) // ' = ' // pad(it%value, 14) // ' ' // &
               pad(unit, 9) // ' ' // it%doc
         end associate
      end do
      write(u, '(a)') '/'
   end subroutine write_deck_help

   !> Write every deck value, defaults included, as namelist text behind prefix.
   subroutine write_echo(u, rec, prefix)
      integer, intent(in) :: u                    !! open formatted unit
      type(deck_record_t), intent(in) :: rec   !! the deck's record
      character(len=*), intent(in) :: prefix      !! e.g. '# '
      character(len=40) :: lhs
      character(len=:), allocatable :: note
      integer :: k
      write(u, '(a)') prefix // 'deck: ' // rec%path // &
         '   (every value; "input" = given in the deck, "default" = not given)'
      associate (items => rec%items)
      do k = 1, size(items)
         if (k == 1) then
            write(u, '(a)') prefix // '&' // items(k)%group
         else if (items(k)%group /= items(k - 1)%group) then
            write(u, '(a)') prefix // '/'
            write(u, '(a)') prefix // '&' // items(k)%group
         end if
         lhs = '   ' // items(k)%name
         note = merge('input  ', 'default', items(k)%given)
         note = trim(note)
         if (len_trim(items(k)%unit) > 0) note = '[' // items(k)%unit // '] ' // note
         write(u, '(a)') prefix // lhs(1:18) // '= ' // pad(items(k)%value, 30) // ' ! ' // note
      end do
      if (size(items) > 0) write(u, '(a)') prefix // '/'
      end associate
   end subroutine write_echo

   !> s padded with blanks to at least n characters.
   pure function pad(s, n) result(r)
      character(len=*), intent(in) :: s   !! text
      integer, intent(in) :: n            !! width
      character(len=max(len(s), n)) :: r
      r = s
   end function pad

   !> A file named in the deck (&load table, &run checkpoint) as the program opens it: a
   !> relative name is relative to the deck's folder (doc/deck.md, "Paths in a deck"), so a
   !> deck runs the same from any working directory; '' stays ''.
   function deck_file(deck, name) result(path)
      type(deck_t), intent(in) :: deck         !! the deck (its path)
      character(len=*), intent(in) :: name     !! the name as the deck gives it
      character(len=:), allocatable :: path
      integer :: k
      path = trim(name)
      if (len(path) == 0) return
      if (path(1:1) == '/') return
      k = index(trim(deck%path), '/', back=.true.)
      if (k > 0 .and. deck%path /= '(built in memory)') path = deck%path(1:k) // path
   end function deck_file

   !> Plausibility warnings (issue 21): values a deck may give (they are valid) that lie
   !> outside the ranges of engineering materials and loads, each naming the variable, its
   !> value and the unit slip it suggests; steps: the run's step count. Empty when &run
   !> warnings = .false.
   function deck_warnings(deck, steps) result(lines)
      type(deck_t), intent(in) :: deck     !! a validated deck
      integer, intent(in) :: steps         !! steps of the run
      character(len=300), allocatable :: lines(:)
      real(wp) :: a
      integer :: j
      character(len=:), allocatable :: sj
      allocate(lines(0))
      if (.not. deck%run%warnings) return
      associate (seg => deck%seg)
         do j = 1, seg%n
            sj = '(' // itoa(j) // ')'
            call out_of_range('&segments: density' // sj, seg%density(j), 100.0_wp, &
               25000.0_wp, 'kg/m^3', 'any solid''s', 'g/cm^3 meant? (' // &
               rtoa(seg%density(j)) // ' g/cm^3 = ' // rtoa(1000.0_wp * seg%density(j)) // &
               ' kg/m^3)')
            call out_of_range('&segments: young' // sj, seg%young(j), 1.0e5_wp, 1.2e12_wp, &
               'Pa', 'any solid''s', unit_guess(seg%young(j), .true.) // ' meant?')
            a = sqrt(seg%young(j) / seg%density(j))
            if (a < 20.0_wp .or. a > 20000.0_wp) call add('&segments: young' // sj // &
               ' and density' // sj // ' give a wave speed of ' // three_digits(a) // &
               ' m/s, outside the solids'' 20..20000 m/s: check their units (Pa, kg/m^3)')
            if (seg%strength(j) > 0.0_wp) call out_of_range('&segments: strength' // sj, &
               seg%strength(j), 1.0e3_wp, 1.0e10_wp, 'Pa', 'any solid''s tensile strength', &
               unit_guess(seg%strength(j), .false.) // ' meant?')
         end do
      end associate
      associate (ld => deck%load)
         if ((ld%kind == 'power' .or. ld%kind == 'exponential') .and. is_set(ld%p0)) then
            if (abs(ld%p0) > 0.0_wp .and. abs(ld%p0) < 1.0e3_wp) call add('&load: p0 = ' // &
               rtoa(ld%p0) // ' Pa is a very small pressure (below 1 kPa): ' // &
               unit_guess(abs(ld%p0), .false.) // ' meant?')
         end if
         if (is_set(ld%t_k)) then
            if (ld%t_k > 10.0_wp) call add('&load: t_k = ' // rtoa(ld%t_k) // ' s is a pulse ' &
               // 'of more than 10 s: ms or us meant? (' // rtoa(ld%t_k) // ' us = ' // &
               rtoa(ld%t_k / 1.0e6_wp) // ' s)')
         end if
         if (is_set(ld%t_cut)) then
            if (ld%t_cut > 10.0_wp) call add('&load: t_cut = ' // rtoa(ld%t_cut) // ' s is ' // &
               'more than 10 s: ms or us meant?')
         end if
      end associate
      if (steps > 10000000) call add('&mesh: the run takes ' // itoa(steps) // ' steps, a ' // &
         'long run: t_end, dt or cells in other units than meant?')
      if (deck%field%kind == 'weibull' .and. is_set(deck%field%scale)) call out_of_range( &
         '&strength_field: scale', deck%field%scale, 1.0e3_wp, 1.0e10_wp, 'Pa', &
         'any solid''s tensile strength', unit_guess(deck%field%scale, .false.) // ' meant?')
      block
         character(len=:), allocatable :: line
         line = transits_warning(deck)
         if (len(line) > 0) call add(line)
      end block
   contains
      !> Append one warning.
      subroutine add(text)
         character(len=*), intent(in) :: text   !! the warning
         lines = [character(len=300) :: lines, text]
      end subroutine add
      !> A warning when x is below lo (with the hint) or above hi.
      subroutine out_of_range(name, x, lo, hi, unit, what, hint)
         character(len=*), intent(in) :: name   !! '&group: variable(j)'
         real(wp), intent(in) :: x              !! the value
         real(wp), intent(in) :: lo             !! the range's low end
         real(wp), intent(in) :: hi             !! its high end
         character(len=*), intent(in) :: unit   !! the value's unit
         character(len=*), intent(in) :: what   !! whose range, e.g. 'any solid''s'
         character(len=*), intent(in) :: hint   !! the unit slip a low value suggests
         character(len=:), allocatable :: range
         range = ' (' // rtoa(lo) // '..' // rtoa(hi) // ' ' // unit // ')'
         if (x < lo) then
            call add(name // ' = ' // rtoa(x) // ' ' // unit // ' is below ' // what // range &
                     // ': ' // hint)
         else if (x > hi) then
            call add(name // ' = ' // rtoa(x) // ' ' // unit // ' is above ' // what // range)
         end if
      end subroutine out_of_range
   end function deck_warnings

   !> The warning ('' : none) when t_end spans more than 1000 transits of the bar's waves
   !> (ms meant for s?): the paper's longest case spans about 110. None where long runs are
   !> the point (long_runs_meant): a run that the waves alone do not end.
   function transits_warning(deck) result(line)
      type(deck_t), intent(in) :: deck     !! a validated deck
      character(len=:), allocatable :: line
      real(wp) :: transit
      integer :: j
      line = ''
      if (long_runs_meant(deck)) return
      transit = 0.0_wp
      do j = 1, deck%seg%n
         transit = transit + deck%seg%length(j) / sqrt(deck%seg%young(j) / deck%seg%density(j))
      end do
      if (transit > 0.0_wp .and. is_set(deck%run%t_end)) then
         if (deck%run%t_end > 1000.0_wp * transit) line = '&run: t_end = ' // &
            rtoa(deck%run%t_end) // ' s is ' // three_digits(deck%run%t_end / transit) // &
            ' transits of the bar (' // three_digits(transit) // ' s each): ms meant? (' // &
            rtoa(deck%run%t_end) // ' ms = ' // rtoa(deck%run%t_end / 1000.0_wp) // ' s)'
      end if
   end function transits_warning

   !> Whether the deck describes a motion over many transits of the waves: gravity (a drop,
   !> a bar settling or hanging), a rigid base (bounces, lift-off and landing), a striking
   !> mass (&impactor: blows, rebounds) or a dry interface (segments that part and strike
   !> again). Time in seconds is then what the deck means (doc/deck.md, "Plausibility
   !> warnings").
   logical function long_runs_meant(deck)
      type(deck_t), intent(in) :: deck     !! a validated deck
      long_runs_meant = abs(deck%run%gravity) > 0.0_wp .or. deck%ends%bottom == 'base' .or. &
                        deck%ends%top == 'base' .or. deck%impactor%on .or. &
                        any(deck%seg%interface(1:deck%seg%n - 1) == 'dry')
   end function long_runs_meant

   !> x with about three significant digits ('0.11', '3.54', '14100', '1.41E-04'), for
   !> messages.
   function three_digits(x) result(text)
      real(wp), intent(in) :: x   !! the number
      character(len=:), allocatable :: text
      character(len=24) :: buf
      character(len=8) :: fmt
      if (abs(x) >= 100.0_wp .and. abs(x) < 1.0e9_wp) then
         text = itoa(nint(x))
      else if (abs(x) >= 0.01_wp .and. abs(x) < 100.0_wp) then
         write(fmt, '(a,i0,a)') '(f0.', 2 - floor(log10(abs(x))), ')'
         write(buf, fmt) x
         text = trim(adjustl(buf))
         if (text(1:1) == '.') text = '0' // text
      else
         write(buf, '(es9.2)') x
         text = trim(adjustl(buf))
      end if
   end function three_digits

   !> The unit a value given in Pa was likely meant in: GPa (a modulus below 1e4) or MPa
   !> ('30 GPa = 3e10 Pa').
   function unit_guess(x, modulus) result(text)
      real(wp), intent(in) :: x   !! a value in Pa that looks too small
      logical, intent(in) :: modulus   !! a modulus (GPa likely), else a stress (MPa)
      character(len=:), allocatable :: text
      if (modulus .and. x < 1.0e4_wp .and. x >= 1.0_wp) then
         text = rtoa(x) // ' GPa = ' // rtoa(1.0e9_wp * x) // ' Pa or ' // rtoa(x) // &
                ' MPa = ' // rtoa(1.0e6_wp * x) // ' Pa'
      else
         text = rtoa(x) // ' MPa = ' // rtoa(1.0e6_wp * x) // ' Pa'
      end if
   end function unit_guess
end module spb_deck
