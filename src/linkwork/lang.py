"""The texts of the report and the drawings, in English and Russian: one table and :func:`t`.

``t("caption.velocity_plan", "ru")`` is ``"План скоростей"``; a text with fields takes them as
keywords, ``t("title.hodograph", "en", name="four-bar", joint="O2")`` (braces of their own doubled, as
``str.format`` reads them).  The Russian texts follow
the notation of the Russian school of the theory of machines and mechanisms (план положений,
план скоростей, полюс p, масштаб μ_v, кинематическая схема, кинематические диаграммы); names from
the mechanism's file and the symbols of quantities stay as they are.  Units are written in each
language's designations (mm and мм).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from linkwork.errors import LinkworkError
from linkwork.limits import excerpt

#: The languages of the texts, the first the default.
LANGUAGES = ("en", "ru")

#: key: (English, Russian).
TEXTS: dict[str, tuple[str, str]] = {
    # ------------------------------------------------------------------ report
    "report.title": ("{name}: linkwork report", "{name}: отчёт linkwork"),
    "caption": ("Figure {number}. {text}", "Рис. {number}. {text}"),
    "at_position": (" at position {position}", " в положении {position}"),
    "section.requirements": ("Requirements", "Требования"),
    "requirements.intro": (
        "This mechanism was synthesised ({kind}) for the requirements below; beside each, what the mechanism "
        "achieves as the analysis measures it over a turn of the crank (dimensions and loads as the file gives "
        "them).",
        "Механизм синтезирован ({kind}) по требованиям, приведённым ниже; рядом с каждым — что механизм "
        "обеспечивает по результатам анализа за оборот кривошипа (размеры и нагрузки — как заданы в файле).",
    ),
    "requirements.head.name": ("Requirement", "Требование"),
    "requirements.head.asked": ("Asked", "Задано"),
    "requirements.head.achieved": ("Achieved", "Обеспечено"),
    "requirements.head.met": ("Met", "Выполнено"),
    "requirements.sense.at_most": ("at most", "не более"),
    "requirements.sense.at_least": ("at least", "не менее"),
    "requirements.as_given": ("as given", "как задано"),
    "requirements.yes": ("yes", "да"),
    "requirements.no": ("NO", "НЕТ"),
    "requirements.theta": (
        "The crank's limit positions (the output {member} at its extremes) are θ = {theta}° apart from the "
        "straight line: the strokes take 180° + θ and 180° − θ of the turn, K = (180° + θ) / (180° − θ) = {k}.",
        "Крайние положения кривошипа (выходное звено {member} в крайних положениях) отстоят от прямой линии на "
        "угол θ = {theta}°: ходы занимают 180° + θ и 180° − θ оборота, K = (180° + θ) / (180° − θ) = {k}.",
    ),
    "caption.limits": (
        "The limit positions of {member} (the second drawn thin) and the angle θ between the crank's limit positions.",
        "Крайние положения {member} (второе — тонкими линиями) и угол θ между крайними положениями кривошипа.",
    ),
    "limits.title": (
        "{name}: limit positions of {member}\nθ = {theta}°, K = {k}",
        "{name}: крайние положения {member}\nθ = {theta}°, K = {k}",
    ),
    "synth.measured": (
        "measured by the analysis (kinematics, forces) of the written file:",
        "измерено анализом (кинематика, силы) записанного файла:",
    ),
    "synth.written": ("written: {out}", "записан: {out}"),
    "synth.unit.deg": ("deg", "град"),
    "synth.unit.Nm": ("N m", "Н·м"),
    "synth.quantity.stroke": ("stroke", "ход"),
    "synth.quantity.swing": ("swing", "угол качания"),
    "synth.quantity.time_ratio": ("time ratio", "коэффициент K"),
    "synth.quantity.largest_pressure_angle": ("largest pressure angle", "наиб. угол давления"),
    "synth.quantity.least_transmission_angle": ("least transmission angle", "наим. угол передачи"),
    "synth.quantity.torque_at_nominal": ("torque at nominal", "момент при номинальной силе"),
    "synth.quantity.upper_stroke": ("upper stroke", "ход верхнего ножа"),
    "synth.quantity.lower_stroke": ("lower stroke", "ход нижнего ножа"),
    "synth.quantity.overlap": ("overlap", "перекрытие ножей"),
    "synth.quantity.opening": ("opening", "раствор ножей"),
    "requirement.stroke": ("stroke H", "ход H"),
    "requirement.swing": ("swing of the rocker", "угол качания коромысла"),
    "requirement.time_ratio": ("time ratio K", "коэффициент изменения средней скорости K"),
    "requirement.max_pressure_angle": ("largest pressure angle", "наибольший угол давления"),
    "requirement.min_transmission_angle": ("least transmission angle", "наименьший угол передачи"),
    "requirement.rod_ratio": ("rod ratio r/l", "отношение r/l"),
    "requirement.offset": ("offset e", "дезаксиал e"),
    "requirement.rocker": ("rocker's length", "длина коромысла"),
    "requirement.frame": ("frame's length", "длина стойки"),
    "requirement.crank": ("crank's length", "длина кривошипа"),
    "requirement.rod": ("rod's length", "длина шатуна"),
    "requirement.force": ("force", "сила"),
    "requirement.working": ("working length of the stroke", "рабочая часть хода"),
    "requirement.before": ("distance before the bottom dead centre", "расстояние до нижней мёртвой точки"),
    "requirement.torque": ("crank's torque limit", "предельный момент на кривошипе"),
    "requirement.upper_stroke": ("upper knife's stroke", "ход верхнего ножа"),
    "requirement.lower_stroke": ("lower knife's stroke", "ход нижнего ножа"),
    "requirement.overlap": ("knives' overlap when closed", "перекрытие ножей"),
    "requirement.opening": ("opening between the knives", "раствор ножей"),
    "section.input": ("Input", "Исходные данные"),
    "section.structure": ("Structure", "Структурный анализ"),
    "input.intro": (
        "What was computed: {name}, over {steps} equal steps of the crank's turn. Lengths in mm, angles in "
        "degrees, masses in kg, moments of inertia in kg·m² about the centre of mass, whatever units the file "
        "declares; the tables and JSON files beside the report are in SI (each column names its unit).",
        "Что рассчитано: {name}, {steps} равных шагов за оборот кривошипа. Длины в мм, углы в градусах, массы в "
        "кг, моменты инерции в кг·м² относительно центра масс, в каких бы единицах ни был задан файл; таблицы и "
        "файлы данных рядом с отчётом — в СИ (единица указана в каждом столбце).",
    ),
    "input.drive": (
        "Drive: joint {joint}, {rpm} rpm ({rad} rad/s) {turn}, uniform; the assembly pose with the crank at "
        "{start}° to the x axis.",
        "Привод: пара {joint}, {rpm} об/мин ({rad} рад/с) {turn}, равномерно; положение сборки — кривошип под "
        "углом {start}° к оси x.",
    ),
    "input.drive.linear": (
        "Drive: joint {joint}, {speed} m/s, uniform; the assembly pose at {start} mm along the guide.",
        "Привод: пара {joint}, {speed} м/с, равномерно; положение сборки — {start} мм вдоль направляющей.",
    ),
    "input.drive.law": (
        "Drive: joint {joint}, by the file's motion law; the assembly pose at {start}° to the x axis.",
        "Привод: пара {joint}, по закону движения из файла; положение сборки — {start}° к оси x.",
    ),
    "input.ccw": ("counter-clockwise", "против часовой стрелки"),
    "input.cw": ("clockwise", "по часовой стрелке"),
    "input.links": (
        "Links: their points in the link's own coordinates, mm; mass properties.",
        "Звенья: точки в собственных координатах звена, мм; массы и моменты инерции.",
    ),
    "input.guides": (
        "Guides: the guide line through a point along an axis, in the guide's coordinates.",
        "Направляющие: линия направляющей через точку вдоль оси, в координатах направляющего звена.",
    ),
    "input.loads": ("External loads, as the file gives them:", "Внешние нагрузки, как они заданы в файле:"),
    "input.machine": (
        "The machine unit (motor, gear, flywheel, δ), as the file gives it:",
        "Машинный агрегат (двигатель, передача, маховик, δ), как он задан в файле:",
    ),
    "input.file": ("The file {file}", "Файл {file}"),
    "input.head.link": ("link", "звено"),
    "input.head.points": ("points, mm", "точки, мм"),
    "input.head.mass": ("mass, kg", "масса, кг"),
    "input.head.com": ("centre of mass, mm", "центр масс, мм"),
    "input.head.inertia": ("moment of inertia, kg·m²", "момент инерции, кг·м²"),
    "input.head.joint": ("joint", "пара"),
    "input.head.guide": ("guide / slider", "направляющая / ползун"),
    "input.head.through": ("through, mm", "через точку, мм"),
    "input.head.axis": ("axis, °", "ось, °"),
    "input.head.load": ("load", "нагрузка"),
    "input.head.type": ("type", "тип"),
    "input.head.given": ("given", "задано"),
    "input.head.part": ("part", "элемент"),
    "section.kinematics": ("Kinematics", "Кинематический анализ"),
    "section.forces": ("Forces (kinetostatics)", "Силовой (кинетостатический) анализ"),
    "section.dynamics": ("Machine dynamics", "Динамика машинного агрегата"),
    "section.impact": ("Impact", "Удар"),
    "section.simulate": ("Run in time", "Движение во времени"),
    "section.animation": ("Animation", "Анимация"),
    "section.warnings": ("Warnings", "Предупреждения"),
    "structure.counts": (
        "Moving links n = {n}, lower pairs p5 = {p5}, higher pairs p4 = {p4}: W = 3n - 2p5 - p4 = {w} "
        "(Chebyshev); redundant constraints q = {q}, mobility W + q = {mobility}.",
        "Подвижных звеньев n = {n}, низших пар p5 = {p5}, высших пар p4 = {p4}; степень подвижности по "
        "формуле Чебышева W = 3n − 2p5 − p4 = {w}; избыточных связей q = {q}, подвижность W + q = {mobility}.",
    ),
    "structure.head.number": ("#", "№"),
    "structure.head.group": ("group", "группа"),
    "structure.head.class": ("class", "класс"),
    "structure.head.order": ("order", "порядок"),
    "structure.head.kind": ("kind", "вид"),
    "structure.head.links": ("links", "звенья"),
    "structure.head.joints": ("joints", "кинематические пары"),
    "structure.formula": ("Structural formula: {formula}", "Формула строения: {formula}"),
    "kin.needs_crank": ("Needs one crank (a revolute drive).", "Нужен один кривошип (вращательная ведущая пара)."),
    "kin.phi.slider": (
        "φ is the crank angle turned from position 0 in the direction of its rotation, 0 to 360°, on every axis "
        "and in every table. Position 0 is the extreme position of the working member {member} at the high end "
        "of its stroke along its guide's axis (the crank at {crank}° to the x axis).",
        "φ — угол поворота кривошипа от положения 0 в направлении его вращения, от 0 до 360°, на всех графиках и "
        "во всех таблицах. Положение 0 — крайнее положение рабочего звена {member}, в котором его координата "
        "вдоль оси направляющей наибольшая (кривошип под углом {crank}° к оси x).",
    ),
    "kin.phi.rocker": (
        "φ is the crank angle turned from position 0 in the direction of its rotation, 0 to 360°, on every axis "
        "and in every table. Position 0 is the extreme position of the output {member} at the "
        "counter-clockwise end of its swing (the crank at {crank}° to the x axis).",
        "φ — угол поворота кривошипа от положения 0 в направлении его вращения, от 0 до 360°, на всех графиках и "
        "во всех таблицах. Положение 0 — крайнее положение выходного {member}, повёрнутого на "
        "наибольший угол против часовой стрелки (кривошип под углом {crank}° к оси x).",
    ),
    "kin.rocker_word": ("rocker", "коромысла"),
    "kin.phi.assembly": (
        "φ is the crank angle turned from position 0, the assembly position (the crank at {crank}° to the "
        "x axis), in the direction of its rotation, 0 to 360°, on every axis and in every table.",
        "φ — угол поворота кривошипа от положения 0, положения сборки (кривошип под углом {crank}° к оси x), "
        "в направлении его вращения, от 0 до 360°, на всех графиках и во всех таблицах.",
    ),
    "head.position": ("position", "положение"),
    "head.phi": ("φ, °", "φ, °"),
    "head.crank_to_x": ("crank to the x axis, °", "кривошип к оси x, °"),
    "head.at_phi": ("at φ, °", "при φ, °"),
    "kin.positions": (
        "The 12 positions: coordinates of the points, mm (x over y):",
        "Двенадцать положений механизма: координаты точек, мм (x над y):",
    ),
    "extremes.slider": ("Strokes of the sliders along their guides' axes:", "Ходы ползунов вдоль осей направляющих:"),
    "extremes.rocker": ("Swings of the rockers:", "Размахи качания коромысел:"),
    "extremes.head.slider.name": ("slider (joint)", "ползун (пара)"),
    "extremes.head.slider.stroke": ("stroke H, mm", "ход H, мм"),
    "extremes.head.slider.low": ("lowest, mm", "наименьшая координата, мм"),
    "extremes.head.slider.high": ("highest, mm", "наибольшая координата, мм"),
    "extremes.head.rocker.name": ("rocker", "коромысло"),
    "extremes.head.rocker.stroke": ("swing β, °", "размах β, °"),
    "extremes.head.rocker.low": ("least angle, °", "наименьший угол, °"),
    "extremes.head.rocker.high": ("largest angle, °", "наибольший угол, °"),
    "extremes.head.phi_low": ("φ at the least, °", "φ при наименьшем, °"),
    "extremes.head.phi_high": ("φ at the largest, °", "φ при наибольшем, °"),
    "extremes.head.k": ("time ratio K", "коэффициент K"),
    "extremes.head.forward": ("+ stroke / other", "ход в + / обратный"),
    "extremes.note": (
        "Time ratio K: the longer stroke's time over the shorter's at uniform crank speed; + stroke / other: the "
        "time of the stroke in the + direction of the guide's axis (the rocker turning counter-clockwise) over "
        "the other's.",
        "K — коэффициент изменения средней скорости: отношение времени более долгого хода ко времени более "
        "короткого при равномерном вращении кривошипа; «ход в + / обратный» — отношение времени хода в "
        "положительном направлении оси направляющей (поворота коромысла против часовой стрелки) ко времени "
        "обратного хода.",
    ),
    "working.title": (
        "The working members at the 12 positions: displacement from position 0, velocity and acceleration:",
        "Рабочие звенья в двенадцати положениях: перемещение от положения 0, скорость и ускорение:",
    ),
    "working.head.s": ("{member}: s, mm", "{member}: s, мм"),
    "working.head.v": ("{member}: v, m/s", "{member}: v, м/с"),
    "working.head.a": ("{member}: a, m/s²", "{member}: a, м/с²"),
    "working.head.psi": ("{member}: ψ, °", "{member}: ψ, °"),
    "working.head.omega": ("{member}: ω, rad/s", "{member}: ω, рад/с"),
    "working.head.epsilon": ("{member}: ε, rad/s²", "{member}: ε, рад/с²"),
    "transmission.head.group": ("transmission angle of group", "угол передачи в группе"),
    "transmission.head.least": ("least, °", "наименьший, °"),
    "event.no-assembly": (
        "Group {group} does not assemble from φ = {start}° to {end}°.",
        "Группа {group} не собирается при φ от {start}° до {end}°.",
    ),
    "event.dead-point": (
        "Group {group}: limit (dead) position near φ = {start}°.",
        "Группа {group}: предельное (мёртвое) положение вблизи φ = {start}°.",
    ),
    "event.singular": (
        "Group {group}: singular position (dead point) near φ = {start}°.",
        "Группа {group}: особое (мёртвое) положение вблизи φ = {start}°.",
    ),
    "event.change-point": (
        "Group {group}: its two assembly modes meet near φ = {start}°; the motion goes on smoothly in the other.",
        "Группа {group}: две её сборки сходятся вблизи φ = {start}°; движение плавно продолжается в другой.",
    ),
    "event.branch-jump": (
        "Group {group}: the solution jumps between φ = {start}° and {end}°; it may have changed its assembly "
        "mode there: check with finer steps.",
        "Группа {group}: решение скачком меняется между φ = {start}° и {end}°, возможно, со сменой сборки: "
        "проверьте с меньшим шагом.",
    ),
    "forces.torque": (
        "Driving torque on the crank: largest {peak} {unit} at φ = {at}°, mean {mean} {unit}.",
        "Уравновешивающий момент на кривошипе: наибольший {peak} {unit} при φ = {at}°, средний {mean} {unit}.",
    ),
    "joints.head.joint": ("joint", "пара"),
    "joints.head.links": ("force of the first link on the second", "сила первого звена на второе"),
    "joints.head.largest": ("largest force, {unit}", "наибольшая сила, {unit}"),
    "joints.unbounded": ("unbounded", "неограничена"),
    "joints.unbounded.note": (
        "Unbounded: the force grows without bound as the crank nears the singular position (a dead or change "
        "point) at the angle given; it has no largest value, and a sample's value there only says how near it fell.",
        "Неограничена: сила неограниченно растёт при подходе кривошипа к особому положению (мёртвому положению или "
        "точке смены сборки) при указанном угле; наибольшего значения у неё нет, а значение в точке разбиения "
        "говорит лишь о том, насколько близко к нему она попала.",
    ),
    "positions.forces": (
        "The driving torque and the forces in the frame's joints at the 12 positions:",
        "Уравновешивающий момент и реакции в опорах стойки в двенадцати положениях:",
    ),
    "efficiency.text": (
        "Friction in the pairs: the efficiency of the cycle η = {cycle} (work of the useful loads {useful} J of "
        "the drive's {drive} J); the instantaneous efficiency 1 − P_friction / P_drive lies between {low} and "
        "{high} where the drive gives power.",
        "Трение в кинематических парах: КПД за цикл η = {cycle} (работа сил полезного сопротивления {useful} Дж "
        "из работы движущих сил {drive} Дж); мгновенный КПД 1 − N_тр / N_д — от {low} до {high} там, где "
        "привод отдаёт мощность.",
    ),
    "efficiency.none": (
        "Friction in the pairs: no efficiency over the cycle (the drive does no work, or the mechanism has no "
        "solution at some positions).",
        "Трение в кинематических парах: КПД за цикл не определён (движущие силы не совершают работы или "
        "в некоторых положениях механизм не имеет решения).",
    ),
    "efficiency.head.joint": ("joint", "пара"),
    "efficiency.head.work": ("work lost to friction, J", "работа сил трения, Дж"),
    "efficiency.head.share": ("of the drive's work, %", "доля работы движущих сил, %"),
    "efficiency.head.peak": ("largest power lost, W", "наибольшая мощность трения, Вт"),
    "friction.locks": (
        "Friction locks the mechanism (self-locking) at φ = {at}°: no drive moves it there.",
        "Самоторможение при φ = {at}°: трение в парах не даёт механизму двигаться.",
    ),
    "friction.does not converge": (
        "The friction in proportion to the pairs' forces does not converge at φ = {at}°.",
        "Силы трения, пропорциональные реакциям, не найдены (итерации не сошлись) при φ = {at}°.",
    ),
    "friction.indeterminate": (
        "Friction is taken as zero at φ = {at}°, where the reactions are indeterminate (a dead point).",
        "Трение принято равным нулю при φ = {at}°: в мёртвом положении реакции не определены.",
    ),
    "positions.head.torque": ("driving torque, {unit}", "уравновешивающий момент, {unit}"),
    "positions.head.support": ("|F| in {joint}, {unit}", "|R| в {joint}, {unit}"),
    "foundation.head": ("foundation", "фундамент"),
    "foundation.head.largest": ("largest", "наибольшее значение"),
    "foundation.shear": ("horizontal force (bolt shear), {unit}", "горизонтальная сила (сдвиг болтов), {unit}"),
    "foundation.pull": ("pull on the bolts, {unit}", "отрывающая сила (растяжение болтов), {unit}"),
    "foundation.push": ("push on the foundation, {unit}", "давление на фундамент, {unit}"),
    "foundation.moment": ("moment about the origin, {unit}", "момент относительно начала координат, {unit}"),
    "checks.title": (
        "Cross-checks (relative discrepancy of the independent methods):",
        "Проверки (относительное расхождение независимых методов):",
    ),
    "checks.head.check": ("check", "проверка"),
    "checks.head.value": ("discrepancy", "расхождение"),
    "check.driving_torque_vs_power_balance": (
        "driving torque against the power balance",
        "уравновешивающий момент и баланс мощностей",
    ),
    "check.foundation_force_vs_momentum": (
        "foundation force against the change of momentum",
        "сила на фундамент и теорема об изменении количества движения",
    ),
    "check.foundation_moment_vs_momentum": (
        "foundation moment against the change of angular momentum",
        "момент на фундамент и теорема об изменении кинетического момента",
    ),
    "check.free_body": ("free body of group {group}", "равновесие группы {group}"),
    "dynamics.head.quantity": ("quantity", "величина"),
    "dynamics.head.value": ("value", "значение"),
    "dynamics.mean_speed": ("mean crank speed, rpm", "средняя частота вращения кривошипа, об/мин"),
    "dynamics.speed_range": ("least and largest crank speed, rpm", "наименьшая и наибольшая частота вращения, об/мин"),
    "dynamics.delta": ("coefficient of speed fluctuation δ", "коэффициент неравномерности хода δ"),
    "dynamics.drive_power": ("mean power of the drive on the crank, W", "средняя мощность привода на кривошипе, Вт"),
    "dynamics.motor_power": ("mean power of the motor at its shaft, W", "средняя мощность двигателя на его валу, Вт"),
    "dynamics.delta_asked": (
        "δ asked for (the flywheel sized for it by Wittenbauer's tangents)",
        "заданный δ (маховик подобран по касательным к диаграмме Виттенбауэра)",
    ),
    "dynamics.delta_true": ("δ of the simulated steady cycle", "δ установившегося режима по расчёту движения"),
    "dynamics.energy_swing": (
        "energy swing: the segment ab between the tangents on the energy axis, J",
        "размах энергии: отрезок между касательными на оси энергии, Дж",
    ),
    "dynamics.inertia_needed": (
        "constant inertia needed on the crank shaft, kg·m²",
        "необходимый постоянный момент инерции на валу кривошипа, кг·м²",
    ),
    "dynamics.why_delta": (
        "Why the simulated δ = {true} differs from the δ = {asked} asked for: the flywheel is sized by an "
        "approximate method, the tangents to Wittenbauer's diagram at the mean speed {rpm} rpm, which is exact "
        "only under a constant drive moment. The simulation integrates the machine unit with the motor's own "
        "characteristic (its torque changes with its speed over the cycle, and the mean speed settles where the "
        "motor balances the load), and so gives the true δ of the machine with that flywheel.",
        "Почему δ = {true} по расчёту движения отличается от заданного δ = {asked}: маховик подобран "
        "приближённым методом — по касательным к диаграмме Виттенбауэра при средней частоте {rpm} об/мин, точным "
        "лишь при постоянном движущем моменте. Расчёт движения интегрирует уравнение машинного агрегата с "
        "механической характеристикой двигателя (его момент меняется со скоростью за цикл, а средняя скорость "
        "устанавливается там, где двигатель уравновешивает нагрузку), и поэтому даёт истинный δ машины с этим "
        "маховиком.",
    ),
    "dynamics.startup": ("start-up time, s", "время разгона, с"),
    "simulate.until": ("length of the run, s", "продолжительность, с"),
    "simulate.start": (
        "crank at the start: angle to x, °; speed, rad/s",
        "кривошип в начале: угол к оси x, °; скорость, рад/с",
    ),
    "simulate.end": (
        "crank at the end: angle to x, °; speed, rad/s",
        "кривошип в конце: угол к оси x, °; скорость, рад/с",
    ),
    "simulate.turned": ("angle turned, °", "угол поворота, °"),
    "simulate.stops": ("the crank stops at, s", "кривошип останавливается в моменты, с"),
    "simulate.motor": ("motor", "двигатель"),
    "dynamics.flywheel": ("flywheel on the {shaft} shaft, kg·m²", "маховик на валу {shaft}, кг·м²"),
    "shaft.motor": ("motor", "двигателя"),
    "shaft.crank": ("crank", "кривошипа"),
    "impact.head.blow": ("blow", "удар"),
    "impact.head.steady": ("blow of the steady cycle", "удар в установившемся цикле"),
    "impact.impulse_on": ("impulse on {at}", "ударный импульс на {at}"),
    "impact.joint": ("impulse in joint {joint}", "импульс реакции в паре {joint}"),
    "impact.energy_lost": ("kinetic energy lost, J", "потерянная кинетическая энергия, Дж"),
    "impact.ideal_com": ("ideal centre of mass", "идеальное положение центра масс"),
    "impact.cycle_failed": ("Working cycle: {reason}", "Рабочий цикл: {reason}"),
    "impact.cycle": (
        "Working cycle with the drive and the tool: {blows} blows per minute.",
        "Рабочий цикл с приводом и инструментом: {blows} ударов в минуту.",
    ),
    "impact.speed": ("impact speed of the striker, m/s", "скорость бойка при ударе, м/с"),
    "impact.crank_speeds": ("crank speed before / after, rad/s", "угловая скорость кривошипа до / после удара, рад/с"),
    "impact.energies": (
        "energy lost in the blow / given to the tool, J",
        "энергия, потерянная при ударе / переданная инструменту, Дж",
    ),
    "impact.work": ("work on the work per cycle, J", "работа над обрабатываемым материалом за цикл, Дж"),
    "impact.motor_power": ("mean motor power, W", "средняя мощность двигателя, Вт"),
    "phase.flight": ("striker free", "свободный ход бойка"),
    "phase.apart": ("striker and tool apart", "боёк и инструмент раздельно"),
    "phase.contact": ("in contact", "в контакте"),
    "phases.head.phase": ("phase", "фаза"),
    "phases.head.freedom": ("W", "W"),
    "phases.head.from": ("from the blow, ms", "от удара, мс"),
    "phases.head.lasts": ("lasts, ms", "длительность, мс"),
    # ------------------------------------------------------------------ captions of the figures
    "caption.scheme": ("Kinematic scheme", "Кинематическая схема"),
    "caption.positions": ("Plan of positions (12 positions)", "План положений (12 положений)"),
    "caption.kinematic_diagrams": (
        "Kinematic diagrams of the working members",
        "Кинематические диаграммы рабочих звеньев",
    ),
    "caption.velocity_plan": ("Velocity plan", "План скоростей"),
    "caption.acceleration_plan": ("Acceleration plan", "План ускорений"),
    "caption.velocity_plans": (
        "Velocity plans of the twelve positions, to one scale",
        "Планы скоростей двенадцати положений в одном масштабе",
    ),
    "caption.acceleration_plans": (
        "Acceleration plans of the twelve positions, to one scale",
        "Планы ускорений двенадцати положений в одном масштабе",
    ),
    "caption.link_angles": (
        "Angles, angular velocities and angular accelerations of the links",
        "Углы, угловые скорости и угловые ускорения звеньев",
    ),
    "caption.driving_torque": ("Driving torque on the crank", "Уравновешивающий момент на кривошипе"),
    "caption.foundation": ("Loads on the foundation", "Нагрузки на фундамент"),
    "caption.hodograph": ("Hodograph of the force in joint {joint}", "Годограф реакции в паре {joint}"),
    "caption.simulate": (
        "Run in time: the angle the crank has turned and its speed, integrated with the exact reduced inertia "
        "and loads at every step (springs and dampers included); its stops marked.",
        "Движение во времени: угол поворота и угловая скорость кривошипа, рассчитанные с точными приведёнными "
        "моментом инерции и моментом сил на каждом шаге (с пружинами и демпферами); остановки отмечены.",
    ),
    "caption.dynamics": (
        "Machine dynamics: reduced moment of inertia and moment of the loads, the crank speed over the steady "
        "cycle, Wittenbauer's diagram",
        "Динамика машинного агрегата: приведённые момент инерции и момент сил, частота вращения кривошипа в "
        "установившемся режиме, диаграмма энергомасс (Виттенбауэра)",
    ),
    # ------------------------------------------------------------------ diagrams
    "axis.crank_angle": ("crank angle φ from position 0, °", "угол поворота кривошипа φ от положения 0, °"),
    "member.slider": ("{link} ({joint})", "{link} ({joint})"),
    "axis.member.s": ("displacement s, mm", "перемещение s, мм"),
    "axis.member.v": ("velocity v, m/s", "скорость v, м/с"),
    "axis.member.a": ("acceleration a, m/s²", "ускорение a, м/с²"),
    "axis.member.psi": ("angle ψ from position 0, °", "угол ψ от положения 0, °"),
    "axis.member.omega": ("angular velocity ω, rad/s", "угловая скорость ω, рад/с"),
    "axis.member.epsilon": ("angular acceleration ε, rad/s²", "угловое ускорение ε, рад/с²"),
    "title.kinematic_diagrams": (
        "{name}: kinematic diagrams of the working members",
        "{name}: кинематические диаграммы рабочих звеньев",
    ),
    "axis.point.position": ("position, mm", "координата, мм"),
    "axis.point.velocity": ("velocity, m/s", "скорость, м/с"),
    "axis.point.acceleration": ("acceleration, m/s²", "ускорение, м/с²"),
    "title.point": ("{name}: point {point}", "{name}: точка {point}"),
    "axis.link.angle": ("angle to the x axis, °", "угол к оси x, °"),
    "axis.link.omega": ("ω, rad/s", "ω, рад/с"),
    "axis.link.epsilon": ("ε, rad/s²", "ε, рад/с²"),
    "title.link_angles": ("{name}: angles of the links", "{name}: углы звеньев"),
    "legend.driving_torque": ("driving torque", r"уравновешивающий момент $M_\mathrm{{ур}}$"),
    "legend.power_balance": ("by the power balance", "по балансу мощностей"),
    "legend.mean": ("mean {value}", "среднее {value}"),
    "axis.torque": ("torque, {unit}", "момент, {unit}"),
    "title.driving_torque": ("{name}: driving torque on the crank", "{name}: уравновешивающий момент на кривошипе"),
    "legend.Fx": ("Fx (bolt shear)", "Fx (сдвиг болтов)"),
    "legend.Fy": ("Fy (+ pulls the bolts)", "Fy (+ отрывает болты)"),
    "legend.shaking_force": ("|shaking force|", "|главный вектор сил инерции|"),
    "legend.foundation_moment": ("moment about the origin", "момент относительно начала координат"),
    "legend.shaking_moment": ("shaking moment", "главный момент сил инерции"),
    "axis.force": ("force, {unit}", "сила, {unit}"),
    "axis.moment": ("moment, {unit}", "момент, {unit}"),
    "title.foundation": ("{name}: loads on the foundation", "{name}: нагрузки на фундамент"),
    "axis.Fx": ("Fx, {unit}", "Fx, {unit}"),
    "axis.Fy": ("Fy, {unit}", "Fy, {unit}"),
    "title.hodograph": (
        "{name}: force in {joint}, positions 0 to 11",
        "{name}: реакция в паре {joint}, положения 0–11",
    ),
    "legend.reduced_inertia": ("reduced moment of inertia J", r"приведённый момент инерции $J_\mathrm{{пр}}$"),
    "legend.reduced_load": ("reduced moment of the loads M", r"приведённый момент сил $M_\mathrm{{пр}}$"),
    "legend.drive_moment": ("constant drive moment", r"постоянный движущий момент $M_\mathrm{{д}}$"),
    "axis.inertia": ("J, kg·m²", r"$J_\mathrm{{пр}}$, кг·м²"),
    "axis.energy": ("energy ΔT, {unit}", "приращение энергии ΔT, {unit}"),
    "legend.position_0": ("position 0", "положение 0"),
    "legend.tangent_max": (r"tangent at $\omega_{{\max}}^2/2$", r"касательная под $\omega_{{\max}}^2/2$"),
    "legend.tangent_min": (r"tangent at $\omega_{{\min}}^2/2$", r"касательная под $\omega_{{\min}}^2/2$"),
    "legend.tangent_segment": (
        "ab = {segment}: constant inertia on the crank\n"
        r"$J = ab\,/\,(\omega_{{\max}}^2/2 - \omega_{{\min}}^2/2)$ = {inertia} kg·m²",
        "отрезок $s$ = {segment}: постоянный момент инерции\n"
        r"$J = s\,/\,(\omega_{{\max}}^2/2 - \omega_{{\min}}^2/2)$ = {inertia} кг·м²",
    ),
    "title.wittenbauer": ("Wittenbauer's diagram", "Диаграмма энергомасс (Виттенбауэра)"),
    "title.dynamics": (
        "Machine dynamics: steady cycle, δ = {delta}",
        "Динамика машинного агрегата: установившийся режим, δ = {delta}",
    ),
    "legend.crank_speed": ("crank speed", "частота вращения кривошипа"),
    "legend.mean_speed": ("mean {value} rpm", "средняя {value} об/мин"),
    "axis.speed": ("crank speed n, rpm", "частота вращения n, об/мин"),
    "axis.time": ("time t, s", "время t, с"),
    "axis.turned": ("angle turned, °", "угол поворота, °"),
    "axis.omega": ("crank speed ω, rad/s", "угловая скорость кривошипа ω, рад/с"),
    "legend.stop": ("the crank stops", "остановка кривошипа"),
    "title.simulate": ("Run in time from t = 0", "Движение во времени от t = 0"),
    # ------------------------------------------------------------------ the scheme, the positions, the plans
    "scheme.title": ("{name}: kinematic scheme", "{name}: кинематическая схема"),
    "drawing.crank": ("crank at {angle}° to x", "угол кривошипа {angle}° к оси x"),
    "drawing.position": (
        "position {position}, crank at {angle}° to x",
        "положение {position}, угол кривошипа {angle}° к оси x",
    ),
    "positions.title": ("{name}: plan of {count} positions", "{name}: план {count} положений"),
    "positions.ccw": (
        "0 at crank {angle}°, then counter-clockwise",
        "положение 0 при угле кривошипа {angle}°, далее против часовой стрелки",
    ),
    "positions.cw": (
        "0 at crank {angle}°, then clockwise",
        "положение 0 при угле кривошипа {angle}°, далее по часовой стрелке",
    ),
    "link.frame": ("frame", "стойка"),
    "plan.velocity": ("velocity plan", "план скоростей"),
    "plan.acceleration": ("acceleration plan", "план ускорений"),
    "plan.scale": ("pole {pole},  {symbol} = {scale} {unit}", "полюс {pole},  масштаб {symbol} = {scale} {unit}"),
    "plan.unit.velocity": ("(m/s)/mm", "(м/с)/мм"),
    "plan.unit.acceleration": ("(m/s²)/mm", "(м/с²)/мм"),
    "plans.velocity": ("{name}: velocity plans of the {count} positions", "{name}: планы скоростей {count} положений"),
    "plans.acceleration": (
        "{name}: acceleration plans of the {count} positions",
        "{name}: планы ускорений {count} положений",
    ),
    "plans.cell": ("{position}: crank {angle}°", "{position}: кривошип {angle}°"),
    # the kinds of vector of each plan, in its legend under the plan's title (Russian: of скорость, ускорение)
    "vector.velocity.absolute": ("absolute (from the pole)", "абсолютная (из полюса)"),
    "vector.velocity.rotation": ("rotation about a point", "относительная (вращение вокруг точки)"),
    "vector.velocity.transport": ("transport (the guide's point)", "переносная (точки направляющей)"),
    "vector.velocity.sliding": ("sliding along the guide", "относительная (вдоль направляющей)"),
    "vector.acceleration.absolute": ("absolute (from the pole)", "абсолютное (из полюса)"),
    "vector.acceleration.normal": ("normal (centripetal)", "нормальное (центростремительное)"),
    "vector.acceleration.tangential": ("tangential", "касательное"),
    "vector.acceleration.transport": ("transport (the guide's point)", "переносное (точки направляющей)"),
    "vector.acceleration.coriolis": ("Coriolis", "кориолисово"),
    "vector.acceleration.sliding": ("sliding along the guide", "относительное (вдоль направляющей)"),
    "animation.crank": ("{name}: crank at {angle}°", "{name}: угол кривошипа {angle}°"),
    # ------------------------------------------------------------------ force plans, Zhukovsky's lever
    "sheet.m_per_mm": ("m/mm", "м/мм"),
    "sheet.n_per_mm": ("N/mm", "Н/мм"),
    "sheet.positions": ("Plan of {count} positions", "План {count} положений"),
    "sheet.velocity": ("Velocity plan", "План скоростей"),
    "sheet.acceleration": ("Acceleration plan", "План ускорений"),
    "sheet.scheme": ("Kinematic scheme", "Кинематическая схема"),
    "sheet.force_plan": ("Force plan: {group}", "План сил: {group}"),
    "sheet.lever": ("Zhukovsky's lever", "Рычаг Жуковского"),
    "sheet.read_off": (", read off the plan", " (по плану сил)"),
    "sheet.legend": ("The arrows of the force plans", "Обозначения на планах сил"),
    "sheet.kinematics": ("Kinematic analysis", "Кинематический анализ"),
    "sheet.kinetostatics": ("Kinetostatic analysis", "Силовой анализ"),
    "forceplans.short": (
        "shorter than {size} mm, named here: {forces}",
        "короче {size} мм, подписаны здесь: {forces}",
    ),
    "forceplans.left_out": (
        "shorter than {size} mm at this scale, not drawn: {forces}",
        "короче {size} мм в этом масштабе, не показаны: {forces}",
    ),
    "forceplans.title": ("{name}: force plans of the groups", "{name}: планы сил групп"),
    "forceplans.cell": ("{group}\nμF = {scale} N/mm", "{group}\nμF = {scale} Н/мм"),
    "forceplans.singular": (
        "a dead point: the reactions are indeterminate",
        "мёртвое положение: реакции неопределимы",
    ),
    "forceplans.unit": ("N/mm", "Н/мм"),
    "forceplans.sheet": (
        "{name}: force plans of {group} at the {count} positions",
        "{name}: планы сил, {group}, в {count} положениях",
    ),
    "forceplans.driving": ("driving link {group}", "начальное звено {group}"),
    "forceplans.not_solved": ("closed by the analytic reactions", "замкнут реакциями аналитического решения"),
    "lever.title": ("{name}: Zhukovsky's lever", "{name}: рычаг Жуковского"),
    "lever.scale": (
        "velocity plan turned by 90°, pole p,  μv = {plan} (m/s)/mm;  forces: μF = {scale} N/mm",
        "план скоростей, повёрнутый на 90°, полюс p,  μv = {plan} (м/с)/мм;  силы: μF = {scale} Н/мм",
    ),
    "lever.moment": ("balancing moment Mb = {moment} N·m", "уравновешивающий момент Mу = {moment} Н·м"),
    "caption.force_plans": ("Force plans of the Assur groups", "Планы сил групп Ассура"),
    "caption.lever": ("Zhukovsky's lever", "Рычаг Жуковского"),
    "caption.force_plan_sheet": (
        "Force plans of {group} at the 12 positions",
        "Планы сил группы {group} в 12 положениях",
    ),
    "caption.levers": ("Zhukovsky's lever at the 12 positions", "Рычаг Жуковского в 12 положениях"),
    "levers.title": (
        "{name}: Zhukovsky's lever at the {count} positions",
        "{name}: рычаг Жуковского в {count} положениях",
    ),
    "levers.cell": (
        "{position}: Mb = {moment} N·m; μF = {scale} N/mm",
        "{position}: Mу = {moment} Н·м; μF = {scale} Н/мм",
    ),
    "levers.scale": (
        "velocity plans turned by 90°, pole p,  μv = {plan} (m/s)/mm",
        "планы скоростей, повёрнутые на 90°, полюс p,  μv = {plan} (м/с)/мм",
    ),
    "kgraph.title": (
        "Kinetostatic analysis by the graphical method, position {position}",
        "Силовой расчёт графоаналитическим методом, положение {position}",
    ),
    "kgraph.where.peak": (
        "Taken where the machine works hardest: the largest driving torque on the working stroke, "
        "Md = {torque} N·m, with {loads} acting (the twelve positions are compared below, this one marked *).",
        "Положение выбрано там, где машина нагружена больше всего: наибольший движущий момент на рабочем ходе, "
        "Мд = {torque} Н·м, при нагрузке: {loads} (ниже это положение сравнивается с двенадцатью и отмечено *).",
    ),
    "kgraph.where.asked": ("The position asked for (--position).", "Положение задано пользователем (--position)."),
    "kgraph.where.angle": (
        "The crank angle asked for (--position).",
        "Угол кривошипа задан пользователем (--position).",
    ),
    "kgraph.where.no_load": ("no process load", "технологическая нагрузка не действует"),
    "kgraph.intro": (
        "The groups are taken from the last one to the driving link. Each is cut free and loaded with its weights, "
        "inertia forces and moments, external loads and the reactions of the groups taken before it. The "
        "tangential components of the reactions at the outer revolute joints come from each link's moments about "
        "the inner joint; the force plan then gives the normal components (or a guide's reaction) by its closing. "
        "Forces in N, moments in N·m, directions in degrees from the x axis counter-clockwise; R12 is the force "
        "of link 1 on link 2.",
        "Группы рассматриваются от последней присоединённой к начальному звену. Каждая группа освобождается от "
        "связей и нагружается силами тяжести, силами и моментами сил инерции, внешними нагрузками и реакциями "
        "ранее рассмотренных групп. Касательные составляющие реакций во внешних вращательных парах находятся из "
        "уравнений моментов сил, действующих на каждое звено, относительно внутреннего шарнира; нормальные "
        "составляющие (или реакция направляющей) — построением плана сил. Силы в Н, моменты в Н·м, направления в "
        "градусах от оси x против часовой стрелки; R12 — сила действия звена 1 на звено 2.",
    ),
    "kgraph.group": ("Group {group} (links {links})", "Группа {group} (звенья {links})"),
    "kgraph.driving": ("Driving link {group}", "Начальное звено {group}"),
    "kgraph.forces_on": ("Forces on it:", "Действующие силы:"),
    "kgraph.couple": ("couple (moment)", "момент пары сил"),
    "kgraph.not_solved": (
        "The textbook's split does not apply to this group: its plan is closed by the reactions of the analytic "
        "solution.",
        "Для этой группы разложение реакций на составляющие не применяется: план сил замкнут реакциями "
        "аналитического решения.",
    ),
    "kgraph.moment": (
        "ΣM_{about}(link {link}) = 0: {unknown}·l + {terms} = 0, l = {length} mm, hence {unknown} = {value} N "
        "(positive: counter-clockwise about {about}).",
        "ΣM_{about}(звено {link}) = 0: {unknown}·l + {terms} = 0, l = {length} мм, откуда {unknown} = {value} Н "
        "(положительна против часовой стрелки относительно {about}).",
    ),
    "kgraph.couple_eq": (
        "ΣM_{about}(link {link}) = 0: {terms} + M = 0, hence the guide's couple M = {value} N·m (where {unknown} "
        "acts).",
        "ΣM_{about}(звено {link}) = 0: {terms} + M = 0, откуда момент направляющей M = {value} Н·м (точка "
        "приложения {unknown}).",
    ),
    "kgraph.plan": (
        "Force plan: {equation}, drawn to μF = {scale} N/mm:",
        "План сил: {equation}, строится в масштабе μF = {scale} Н/мм:",
    ),
    "kgraph.found": ("From the plan: {reactions}.", "Из плана сил: {reactions}."),
    "kgraph.balancing": (
        "The moments about the pivot give the balancing moment Mb = {value} N·m (counter-clockwise positive).",
        "Из уравнения моментов относительно оси вращения уравновешивающий момент Mу = {value} Н·м "
        "(положителен против часовой стрелки).",
    ),
    "kgraph.lever": (
        "Zhukovsky's lever: the balancing moment from the lever's moments about the pole, beside the driving "
        "torque of the kinetostatic solution (difference relative to the largest torque).",
        "Рычаг Жуковского: уравновешивающий момент из уравнения моментов относительно полюса повёрнутого плана "
        "скоростей и момент, найденный силовым расчётом (разность отнесена к наибольшему моменту).",
    ),
    "kgraph.head.force": ("force", "сила"),
    "kgraph.head.what": ("what", "что это"),
    "kgraph.head.value": ("value, N (N·m)", "величина, Н (Н·м)"),
    "kgraph.head.length": ("on the plan, mm", "на плане, мм"),
    "kgraph.head.direction": ("direction, °", "направление, °"),
    "kgraph.head.lever": ("Mb by the lever, N·m", "Mу по рычагу, Н·м"),
    "kgraph.head.kinetostatic": ("driving torque, N·m", "момент из силового расчёта, Н·м"),
    "kgraph.head.difference": ("difference", "разность"),
    "force.weight": ("weight", "сила тяжести"),
    "force.inertia": ("inertia force", "сила инерции"),
    "force.load": ("external load", "внешняя нагрузка"),
    "force.known": ("reaction of a group taken before", "реакция ранее рассмотренной группы"),
    "force.tangential": ("tangential component", "касательная составляющая"),
    "force.normal": ("normal component", "нормальная составляющая"),
    "force.reaction": ("reaction found", "искомая реакция"),
    "force.internal": ("reaction in the inner joint", "реакция во внутренней паре"),
    "force.balancing": ("balancing force", "уравновешивающая сила"),
    # ------------------------------------------------------------------ units
    "unit.mm": ("mm", "мм"),
    "unit.m_s": ("m/s", "м/с"),
    "unit.m_s2": ("m/s²", "м/с²"),
    "kplan.title": (
        "The velocity and acceleration plans worked out, position {position}",
        "Построение планов скоростей и ускорений, положение {position}",
    ),
    "kplan.velocity": (
        "Velocity plan: pole {pole}, μv = {scale} (m/s)/mm",
        "План скоростей: полюс {pole}, μv = {scale} (м/с)/мм",
    ),
    "kplan.acceleration": (
        "Acceleration plan: pole {pole}, μa = {scale} (m/s²)/mm",
        "План ускорений: полюс {pole}, μa = {scale} (м/с²)/мм",
    ),
    "kplan.rotation": (
        "{name} ⊥ {line}: {name} = {value} {unit}, {segment}; {w} = {name} / l{line} = {value} / {l} m = {omega} rad/s",
        "{name} ⊥ {line}: {name} = {value} {unit}, {segment}; {w} = {name} / l{line} = {value} / {l} м = {omega} рад/с",
    ),
    "kplan.normal": (
        "{name} ∥ {line}, from {point} to {about}: {name} = {w}²·l{line} = {omega}²·{l} m = {value} {unit}, {segment}",
        "{name} ∥ {line}, от {point} к {about}: {name} = {w}²·l{line} = {omega}²·{l} м = {value} {unit}, {segment}",
    ),
    "kplan.tangential": (
        "{name} ⊥ {line}, measured on the plan: {segment}, {name} = {mm}·{scale} = {value} {unit}; "
        "{e} = {name} / l{line} = {eps} rad/s²",
        "{name} ⊥ {line}, измерено на плане: {segment}, {name} = {mm}·{scale} = {value} {unit}; "
        "{e} = {name} / l{line} = {eps} рад/с²",
    ),
    "kplan.coriolis": (
        "{name} = 2·ω·v_r (ω of the guide): {name} = {value} {unit}, {segment}",
        "{name} = 2·ω·v_r (ω направляющей): {name} = {value} {unit}, {segment}",
    ),
    "kplan.sliding": (
        "{name} ∥ the guide, measured on the plan: {segment}, {name} = {value} {unit}",
        "{name} ∥ направляющей, измерено на плане: {segment}, {name} = {value} {unit}",
    ),
    "kplan.transport": (
        "{name}, of the guide's coincident point: {name} = {value} {unit}, {segment}",
        "{name}, точки направляющей, совпадающей с ползуном: {name} = {value} {unit}, {segment}",
    ),
    "kplan.vector": ("{name} = {value} {unit}, {segment}", "{name} = {value} {unit}, {segment}"),
    "kplan.absolute": ("The points' absolute vectors, from the pole:", "Абсолютные векторы точек, от полюса:"),
    "unit.deg": ("°", "°"),
    "unit.N": ("N", "Н"),
    "unit.kN": ("kN", "кН"),
    "unit.Nm": ("N·m", "Н·м"),
    "unit.kNm": ("kN·m", "кН·м"),
    # ------------------------------------------------------------------ sizing
    "section.sizing": (
        "Sizing",
        "Подбор и расчёт деталей",
    ),
    "sizing.intro": (
        "The parts sized from the loads of the cycle at the file's crank speed (linkwork size; the formulas in "
        "the manual's page on sizing). Catalogue values are typical values.",
        "Детали, подобранные по нагрузкам цикла при частоте вращения кривошипа из файла (linkwork size; "
        "формулы в разделе руководства о расчёте деталей). Данные каталогов — типичные значения.",
    ),
    "sizing.inputs": (
        "Inputs of the sizing, defaults included:",
        "Исходные данные расчёта, с принятыми по умолчанию:",
    ),
    "sizing.failed": (
        "The sizing could not be done: {why}",
        "Расчёт не выполнен: {why}",
    ),
    "sizing.missing": (
        "Not sized: {part}: {why}",
        "Не рассчитано: {part}: {why}",
    ),
    "sizing.table.motor": (
        "Motor, gear and flywheel, chosen from the catalogue and checked by a run of the machine",
        "Двигатель, передача и маховик, выбранные по каталогу и проверенные расчётом движения",
    ),
    "sizing.table.rolling": (
        "Rolling bearings by ISO 281: equivalent load P and the load rating C needed",
        "Подшипники качения по ISO 281: эквивалентная нагрузка P и требуемая грузоподъёмность C",
    ),
    "sizing.table.plain": (
        "Plain bushes: pressure p, sliding speed v and pv",
        "Подшипники скольжения: давление p, скорость скольжения v и pv",
    ),
    "sizing.table.guides": (
        "Guides: normal force and pressure per length",
        "Направляющие: нормальная сила и погонная нагрузка",
    ),
    "sizing.table.joints": (
        "Joints: what governs each: the pin and its bush are one diameter (the larger of their least), or a rolling "
        "bearing of the rating C instead of the bush, where the joint turns far enough for one",
        "Шарниры: что определяет размер каждого: ось и её втулка — один диаметр (больший из наименьших), или "
        "подшипник качения с грузоподъёмностью C вместо втулки, где шарнир поворачивается достаточно для него",
    ),
    "sizing.table.shaft": (
        "The crank's main shaft on two bearings: each bearing's share of the force and the shaft's bending",
        "Главный вал кривошипа на двух подшипниках: доля силы на каждый подшипник и изгиб вала",
    ),
    "sizing.row.bearings' spacing": ("bearings' spacing", "расстояние между подшипниками"),
    "sizing.row.crank's overhang outside bearing 1 (- : midway)": (
        "crank's overhang outside bearing 1 (- : midway)",
        "вылет кривошипа за подшипник 1 (- : посередине)",
    ),
    "sizing.row.spacing and overhang from the file": (
        "spacing and overhang from the file",
        "расстояние и вылет из файла",
    ),
    "sizing.row.share of the force on bearing 1": ("share of the force on bearing 1", "доля силы на подшипник 1"),
    "sizing.row.share of the force on bearing 2": ("share of the force on bearing 2", "доля силы на подшипник 2"),
    "sizing.row.peak force of the crank's pivot": (
        "peak force of the crank's pivot",
        "наибольшая сила в опоре кривошипа",
    ),
    "sizing.row.largest bending moment": ("largest bending moment", "наибольший изгибающий момент"),
    "sizing.row.least solid shaft for bending": ("least solid shaft for bending", "наименьший сплошной вал по изгибу"),
    "sizing.word.no": ("no", "нет"),
    "sizing.col.pin d [mm]": ("pin d [mm]", "d оси, мм"),
    "sizing.col.pin by": ("pin by", "ось по"),
    "sizing.col.bush d [mm]": ("bush d [mm]", "d втулки, мм"),
    "sizing.col.bush by": ("bush by", "втулка по"),
    "sizing.col.d to make [mm]": ("d to make [mm]", "d к исполнению, мм"),
    "sizing.col.governs": ("governs", "определяет"),
    "sizing.col.rolling C [kN]": ("rolling C [kN]", "C подшипника качения, кН"),
    "sizing.col.rolling bearing": ("rolling bearing", "подшипник качения"),
    "sizing.word.pin bending": ("pin bending", "изгиб оси"),
    "sizing.word.pin shear": ("pin shear", "срез оси"),
    "sizing.word.bush p": ("bush p", "p втулки"),
    "sizing.word.bush pv": ("bush pv", "pv втулки"),
    "sizing.word.given": ("given", "задан"),
    "sizing.motor_given": (
        "The motor is the file's (machine.motor): it is taken as given, not chosen from the catalogue (sizing: "
        "{{motor: true}} chooses one).",
        "Двигатель задан в файле: он принят как задан, из каталога не подбирается (подбор двигателя задаётся "
        "в разделе подбора деталей файла).",
    ),
    "sizing.word.ok": ("ok", "годится"),
    "sizing.table.pins": (
        "Pins in double shear",
        "Оси (пальцы) при двухсрезном соединении",
    ),
    "sizing.table.links": (
        "Links as bars: axial force, bending moment, stress and fatigue (modified Goodman line)",
        "Звенья как стержни: продольная сила, изгибающий момент, напряжения и усталость (линия Гудмана)",
    ),
    "sizing.table.bolts": (
        "Foundation bolts: the largest force opening the joint at each",
        "Фундаментные болты: наибольшая отрывающая сила у каждого",
    ),
    "sizing.table.preload": (
        "Foundation bolts: preload and thread",
        "Фундаментные болты: затяжка и резьба",
    ),
    "sizing.col.quantity": ("quantity", "величина"),
    "sizing.col.value": ("value", "значение"),
    "sizing.col.unit": ("unit", "ед."),
    "sizing.col.joint": ("joint", "пара"),
    "sizing.col.motion": ("motion", "движение"),
    "sizing.col.swing [deg]": ("swing [deg]", "размах, °"),
    "sizing.col.F max [kN]": ("F max [kN]", "F макс, кН"),
    "sizing.col.at phi [deg]": ("at phi [deg]", "при φ, °"),
    "sizing.col.F mean [kN]": ("F mean [kN]", "F ср, кН"),
    "sizing.col.n eq [rpm]": ("n eq [rpm]", "n экв, об/мин"),
    "sizing.col.P [kN]": ("P [kN]", "P, кН"),
    "sizing.col.C needed [kN]": ("C needed [kN]", "C треб, кН"),
    "sizing.col.d [mm]": ("d [mm]", "d, мм"),
    "sizing.col.b [mm]": ("b [mm]", "b, мм"),
    "sizing.col.d given": ("d given", "d задан"),
    "sizing.col.p mean [MPa]": ("p mean [MPa]", "p ср, МПа"),
    "sizing.col.p max [MPa]": ("p max [MPa]", "p макс, МПа"),
    "sizing.col.v max [m/s]": ("v max [m/s]", "v макс, м/с"),
    "sizing.col.pv mean [MPa m/s]": ("pv mean [MPa m/s]", "pv ср, МПа·м/с"),
    "sizing.col.pv max [MPa m/s]": ("pv max [MPa m/s]", "pv макс, МПа·м/с"),
    "sizing.col.over the limits": ("over the limits", "превышено"),
    "sizing.col.N max [kN]": ("N max [kN]", "N макс, кН"),
    "sizing.col.N mean [kN]": ("N mean [kN]", "N ср, кН"),
    "sizing.col.M max [kN m]": ("M max [kN m]", "M макс, кН·м"),
    "sizing.col.L [mm]": ("L [mm]", "L, мм"),
    "sizing.col.q max [kN/m]": ("q max [kN/m]", "q макс, кН/м"),
    "sizing.col.tau [MPa]": ("tau [MPa]", "τ, МПа"),
    "sizing.col.sigma bending [MPa]": ("sigma bending [MPa]", "σ изг, МПа"),
    "sizing.col.p [MPa]": ("p [MPa]", "p, МПа"),
    "sizing.col.link": ("link", "звено"),
    "sizing.col.ends": ("ends", "концы"),
    "sizing.col.section": ("section", "сечение"),
    "sizing.col.M at phi [deg]": ("M at phi [deg]", "M при φ, °"),
    "sizing.col.M at s [mm]": ("M at s [mm]", "M при s, мм"),
    "sizing.col.N there [kN]": ("N there [kN]", "N там же, кН"),
    "sizing.col.N at phi [deg]": ("N at phi [deg]", "N при φ, °"),
    "sizing.col.sigma max [MPa]": ("sigma max [MPa]", "σ макс, МПа"),
    "sizing.col.sigma at phi [deg]": ("sigma at phi [deg]", "σ при φ, °"),
    "sizing.col.sigma_a [MPa]": ("sigma_a [MPa]", "σ_a, МПа"),
    "sizing.col.sigma_m [MPa]": ("sigma_m [MPa]", "σ_m, МПа"),
    "sizing.col.Goodman n": ("Goodman n", "n по Гудману"),
    "sizing.col.bolt": ("bolt", "болт"),
    "sizing.col.x [mm]": ("x [mm]", "x, мм"),
    "sizing.col.y [mm]": ("y [mm]", "y, мм"),
    "sizing.col.F open max [kN]": ("F open max [kN]", "F отрыва макс, кН"),
    "sizing.row.motor": ("motor", "двигатель"),
    "sizing.row.rated power": ("rated power", "номинальная мощность"),
    "sizing.row.rated speed": ("rated speed", "номинальная частота вращения"),
    "sizing.row.synchronous speed": ("synchronous speed", "синхронная частота вращения"),
    "sizing.row.rated torque": ("rated torque", "номинальный момент"),
    "sizing.row.breakdown torque": ("breakdown torque", "критический (максимальный) момент"),
    "sizing.row.rotor inertia": ("rotor inertia", "момент инерции ротора"),
    "sizing.row.mass": ("mass", "масса"),
    "sizing.row.mean power needed at the motor shaft": (
        "mean power needed at the motor shaft",
        "требуемая средняя мощность на валу двигателя",
    ),
    "sizing.row.load of the rating (mean power / rated)": (
        "load of the rating (mean power / rated)",
        "загрузка (средняя мощность / номинальная)",
    ),
    "sizing.row.gear ratio (rated speed / crank speed)": (
        "gear ratio (rated speed / crank speed)",
        "передаточное отношение (номинальная частота / частота кривошипа)",
    ),
    "sizing.row.gear efficiency": ("gear efficiency", "КПД передачи"),
    "sizing.row.flywheel on the motor shaft": ("flywheel on the motor shaft", "маховик на валу двигателя"),
    "sizing.row.delta asked": ("delta asked", "заданный δ"),
    "sizing.row.delta of the run": ("delta of the run", "δ по расчёту движения"),
    "sizing.row.start-up time": ("start-up time", "время разгона"),
    "sizing.row.peak motor torque of the steady cycle": (
        "peak motor torque of the steady cycle",
        "наибольший момент двигателя в установившемся режиме",
    ),
    "sizing.row.  at crank angle phi": ("  at crank angle phi", "  при угле кривошипа φ"),
    "sizing.row.peak / breakdown torque (allowed: reserve)": (
        "peak / breakdown torque (allowed: reserve)",
        "наибольший / критический момент (допускается: запас)",
    ),
    "sizing.row.reserve": ("reserve", "запас"),
    "sizing.row.RMS motor torque (heating)": ("RMS motor torque (heating)", "среднеквадратичный момент (нагрев)"),
    "sizing.row.RMS / rated torque (allowed: 1)": (
        "RMS / rated torque (allowed: 1)",
        "среднеквадратичный / номинальный момент (допускается: 1)",
    ),
    "sizing.row.preload per bolt": ("preload per bolt", "затяжка одного болта"),
    "sizing.row.decided by": ("decided by", "определяется"),
    "sizing.row.  at phi": ("  at phi", "  при φ"),
    "sizing.row.largest bolt force": ("largest bolt force", "наибольшая сила в болте"),
    "sizing.row.stress area needed": ("stress area needed", "требуемая площадь сечения резьбы"),
    "sizing.row.thread": ("thread", "резьба"),
    "sizing.row.its stress area": ("its stress area", "её площадь сечения"),
    "sizing.word.turns": ("turns", "вращается"),
    "sizing.word.rocks": ("rocks", "качается"),
    "sizing.word.yes": ("yes", "да"),
    "sizing.word.least": ("least", "наименьший"),
    "sizing.word.none": ("none", "нет"),
    "sizing.word.opening": ("opening", "нераскрытие стыка"),
    "sizing.word.sliding": ("sliding", "несдвигаемость стыка"),
    "sizing.unit.kW": ("kW", "кВт"),
    "sizing.unit.rpm": ("rpm", "об/мин"),
    "sizing.unit.N m": ("N m", "Н·м"),
    "sizing.unit.kg m^2": ("kg m^2", "кг·м²"),
    "sizing.unit.kg": ("kg", "кг"),
    "sizing.unit.s": ("s", "с"),
    "sizing.input.life_h": ("rating life L10h, h", "расчётный ресурс подшипников L10h, ч"),
    "sizing.input.bearing_kind": ("rolling bearings", "подшипники качения"),
    "sizing.input.delta": ("coefficient of speed fluctuation", "коэффициент неравномерности хода"),
    "sizing.input.gear_efficiency": ("gear efficiency", "КПД передачи"),
    "sizing.input.reserve": (
        "peak motor torque at most this share of the breakdown torque",
        "доля критического момента, которую может занять пиковый момент двигателя",
    ),
    "sizing.input.catalogue": ("motor catalogue", "каталог двигателей"),
    "sizing.input.synchronous_rpm": ("synchronous speed, rpm", "синхронная частота вращения, об/мин"),
    "sizing.input.steel": ("steel of the pins and links", "сталь осей и звеньев"),
    "sizing.input.pin_safety": ("safety factor of the pins", "коэффициент запаса осей"),
    "sizing.input.bush": ("bush of the plain bearings", "втулка подшипников скольжения"),
    "sizing.input.width_ratio": ("bush width over diameter", "отношение ширины втулки к диаметру"),
    "sizing.input.bolt_class": ("property class of the bolts", "класс прочности болтов"),
    "sizing.input.bolt_safety": ("safety factor of the bolts", "коэффициент запаса болтов"),
    "sizing.input.joint_safety": (
        "safety factor against opening and sliding",
        "коэффициент запаса против раскрытия и сдвига стыка",
    ),
    "sizing.input.friction": ("friction coefficient of the bed joint", "коэффициент трения в стыке станины"),
    "sizing.input.load_factor": ("load factor of the bolts", "коэффициент основной нагрузки болтов"),
    "sizing.input.steps": ("samples over the turn", "число положений за оборот"),
    "sizing.input.crank_rpm": ("crank speed, rpm", "частота вращения кривошипа, об/мин"),
    "sizing.input.loads": ("loads", "нагрузки"),
    "sizing.input.masses": ("masses", "массы"),
    "sizing.word.the file's (or its default rule)": (
        "the file's (or its default rule)",
        "из файла (или по его правилу по умолчанию)",
    ),
    "sizing.word.ball": ("ball", "шариковые"),
    "sizing.word.roller": ("roller", "роликовые"),
    "sizing.word.C45 normalised": ("C45 normalised", "сталь 45, нормализованная"),
    "sizing.word.tin bronze CuSn12 greased": (
        "tin bronze CuSn12 greased",
        "оловянная бронза CuSn12, с консистентной смазкой",
    ),
    "sizing.word.motors.csv (bundled, typical values)": (
        "motors.csv (bundled, typical values)",
        "каталог из комплекта пакета (типичные значения)",
    ),
    "sizing.word.kinetostatics at the file's uniform crank speed": (
        "kinetostatics at the file's uniform crank speed",
        "кинетостатика при равномерном вращении кривошипа с частотой из файла",
    ),
    "sizing.word.nothing: the loads never lift the bed nor push it sideways beyond its friction": (
        "nothing: the loads never lift the bed nor push it sideways beyond its friction",
        "не требуется: нагрузки не отрывают станину и не сдвигают её сверх силы трения",
    ),
    "sizing.word.motor": ("motor", "двигатель"),
    "sizing.word.not asked": ("not asked", "не запрошен"),
    "sizing.least_round": ("least round d {d} mm", "наименьший круглый d {d} мм"),
    "sizing.rolling_no": (
        "no: swings {swing} < {pitch} deg between its elements",
        "нет: размах {swing}° меньше {pitch}° между телами качения",
    ),
    "sizing.joints": ("joints {joints}", "шарниры {joints}"),
    "sizing.unbounded": (
        "the force grows without bound as the crank nears the singular position at phi {phi} deg: no pin, bush or "
        "bearing holds it",
        "сила неограниченно растёт при подходе кривошипа к особому положению при φ = {phi}°: её не выдержит ни "
        "ось, ни втулка, ни подшипник",
    ),
    "sizing.word.given too small": ("given too small", "задан слишком малым"),
    "sizing.word.not sized: unbounded": ("not sized: unbounded", "не рассчитан: сила неограничена"),
    "sizing.unit.deg": ("deg", "°"),
    "sizing.unit.kN": ("kN", "кН"),
    "sizing.unit.mm^2": ("mm^2", "мм²"),
    "sizing.unit.mm": ("mm", "мм"),
    "sizing.unit.kN m": ("kN m", "кН·м"),
    "unit.J": ("J", "Дж"),
    "unit.kJ": ("kJ", "кДж"),
    "unit.Ns": ("N·s", "Н·с"),
}


def check_lang(lang: str) -> None:
    """Raise :class:`~linkwork.errors.LinkworkError` unless ``lang`` is one of :data:`LANGUAGES`."""
    if lang not in LANGUAGES:
        raise LinkworkError(f"--lang: expected one of {', '.join(LANGUAGES)}, got {excerpt(lang)!r}")


def link_named(name: str, translate: Callable[[str], str]) -> str:
    """A link's name as a table writes it: the frame (the link the file calls ``frame``) in the report's language
    (``translate``: a key to its text, e.g. ``"стойка"``), every other link by its name in the file."""
    return translate("link.frame") if name == "frame" else name


def kind_named(kind: str, name: str) -> str:
    """``rocker output``: a member's kind and its name, the word once where the name is the kind's word
    (``rocker``, not ``rocker rocker``)."""
    return kind if name.strip().lower() == kind.lower() else f"{kind} {name}"


def group_kind(kind: str, lang: str) -> str:
    """An Assur group's kind (``RRP``) in the notation of the language (``ВВП`` in Russian: вращательная,
    поступательная)."""
    return kind.translate(str.maketrans("RP", "ВП")) if lang == "ru" else kind


def group_label(label: str, lang: str) -> str:
    """A group's label (``II(4,5) RRP``) with its kind in the notation of the language."""
    head, _, kind = label.partition(" ")
    return f"{head} {group_kind(kind, lang)}" if kind else head


#: The keys and words of a file's loads and machine as the report's input section shows them, in Russian (in
#: English they stay as the file writes them).
FILE_WORDS_RU = {
    "tools": "инструменты",
    "at": "точка",
    "on": "звено",
    "joint": "пара",
    "axis": "ось",
    "workpiece": "заготовка",
    "penetration": "относительное внедрение",
    "force": "сила",
    "moment": "момент",
    "value": "величина",
    "power": "мощность",
    "speed": "частота вращения",
    "synchronous": "синхронная частота вращения",
    "breakdown": "кратность максимального момента",
    "inertia": "момент инерции",
    "ratio": "передаточное отношение",
    "efficiency": "КПД",
    "process": "технологическая",
    "induction": "асинхронный",
    "motor": "двигатель",
    "gear": "передача",
    "flywheel": "маховик",
    "type": "тип",
    "delta": "δ",
}

#: Units as a file writes them, in Russian.
FILE_UNITS_RU = {
    "kg*m^2": "кг·м²",
    "N*m": "Н·м",
    "kN*m": "кН·м",
    "rad/s": "рад/с",
    "rpm": "об/мин",
    "kN": "кН",
    "kW": "кВт",
    "deg": "°",
    "mm": "мм",
    "kg": "кг",
    "m": "м",
    "N": "Н",
    "W": "Вт",
    "s": "с",
    "h": "ч",
}


def file_word(word: str, lang: str) -> str:
    """A key or word of a file (``power``, ``process``) in ``lang``: itself in English, in Russian its Russian
    (:data:`FILE_WORDS_RU`), a name of the file's own as it is."""
    return FILE_WORDS_RU.get(word, word) if lang == "ru" else word


def file_value(text: str, lang: str) -> str:
    """A value as a file writes it (``250 kN``, ``0.03 kg*m^2``, ``90 deg``) in ``lang``: in Russian its units in
    Russian and a decimal comma (``250 кН``, ``0,03 кг·м²``, ``90°``); in English as written."""
    import re

    if lang != "ru":
        return text
    units = "|".join(re.escape(u) for u in FILE_UNITS_RU)

    def one(m: re.Match[str]) -> str:
        number, unit = m.group(1).replace(".", ","), FILE_UNITS_RU[m.group(2)]
        return f"{number}{unit}" if unit == "°" else f"{number} {unit}"

    out = re.sub(rf"(-?\d+(?:\.\d+)?(?:e[-+]?\d+)?)\s*({units})(?![\w*^/])", one, text)
    return re.sub(r"(?<![\w.])(-?\d+)\.(\d+)(?![\w.])", r"\1,\2", out)


_SUPERSCRIPT = str.maketrans("-+0123456789", "⁻⁺⁰¹²³⁴⁵⁶⁷⁸⁹")


def russian_numbers(text: str) -> str:
    """The numbers of a text as Russian writes them: a decimal comma (``294.3`` -> ``294,3``), a power of ten
    for an exponent (``2.5e+05`` -> ``2,5·10⁵``), numbers with decimals listed apart by semicolons
    (``(7.465, 49.77)`` -> ``(7,465; 49,77)``); a number glued to a name (``O1.x``, ``v1.2``) as it is."""
    import re

    def power(m: re.Match[str]) -> str:
        exponent = str(int(m.group(2)))
        return f"{m.group(1)}·10{exponent.translate(_SUPERSCRIPT)}"

    def apart(m: re.Match[str]) -> str:  # numbers with decimals listed apart by semicolons: (7,465; 49,77)
        return m.group(1) + ("; " if "." in m.group(1) + m.group(2) else ", ")

    text = re.sub(r"(?<![\w.])(-?\d+(?:\.\d+)?), (?=(-?\d+(?:\.\d+)?)(?![\w.]))", apart, text)
    after = r"(?![A-Za-zА-Яа-яЁё_0-9.])"  # not glued to a name ("²" may follow: 3.142² -> 3,142²)
    out = re.sub(rf"(?<![\w.])(-?\d+(?:\.\d+)?)e([-+]?\d+){after}", power, text)
    return re.sub(rf"(?<![\w.,])(-?\d+)\.(\d+){after}", r"\1,\2", out)


def russian_html(page: str) -> str:
    """:func:`russian_numbers` on the text of an HTML page, not on its tags, styles, scripts and ``<pre>`` blocks
    (a file's own text)."""
    import re

    parts = re.split(r"(<pre.*?</pre>|<style.*?</style>|<script.*?</script>|<[^>]*>)", page, flags=re.S)
    return "".join(p if k % 2 else russian_numbers(p) for k, p in enumerate(parts))


def t(key: str, lang: str = "en", /, **values: Any) -> str:
    """The text ``key`` in ``lang`` (``"en"`` or ``"ru"``), its fields filled from ``values``.

    Raises
    ------
    KeyError
        For a key the table does not have.
    LinkworkError
        For a language it does not have.
    """
    check_lang(lang)
    return TEXTS[key][LANGUAGES.index(lang)].format(**values)
