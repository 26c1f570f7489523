#include "ParcelDeposition.H"
#include "Pstream.H"
#include "IPstream.H"
#include "OPstream.H"
#include "ops.H"
#include "mathematicalConstants.H"

#include <algorithm>
#include <thread>
#include <vector>

Foam::cosim::ParcelDeposition::ParcelDeposition(const fvMesh& mesh, label divisions)
:
    mesh_(mesh),
    locator_(mesh),
    satellites_(divisions),
    threads_
    (
        label(std::min(4u, std::max(1u, std::thread::hardware_concurrency())))
    ),
    routing_(locator_.bounds())
{}


Foam::cosim::ParcelDeposition::~ParcelDeposition()
{
    if (prepared_)
    {
        prepared_->result.wait();
    }
}


Foam::cosim::ParcelDeposition::Placement Foam::cosim::ParcelDeposition::compute
(
    const std::vector<std::int64_t>& ids,
    const std::vector<double>& position,
    const std::vector<double>& radius,
    label threads
) const
{
    Placement out;
    const label n = label(ids.size());
    const label nSat = satellites_.size();
    out.n = n;

    if (Pstream::parRun())
    {
        divideByProcessor(out);
    }
    locateCentres(ids, position, out);

    // 2. satellite points, seeded by the centre cell. Independent per parcel, so on one
    //    processor they are split over threads: the DEM waits for these samples, its core is
    //    free. Each point is located exactly as by one thread (same cells, same order of work
    //    within a parcel).
    labelList satCell(n*nSat, label(-1));
    labelList satOwner(n*nSat, labelMax);
    auto satellitesOf = [&](label begin, label end)
    {
        locateSatellites(position, radius, out, begin, end, satCell, satOwner);
    };
    const label nThreads = (Pstream::parRun() || n < 512) ? 1 : threads;
    std::vector<std::thread> helpers;
    for (label t = 1; t < nThreads; ++t)
    {
        helpers.emplace_back(satellitesOf, n*t/nThreads, n*(t + 1)/nThreads);
    }
    satellitesOf(0, n/nThreads);
    for (std::thread& h : helpers)
    {
        h.join();
    }
    if (Pstream::parRun())
    {
        agreeOnShared(out.shared, nSat, satOwner);
    }

    collectDeposits(satCell, satOwner, out);
    return out;
}


void Foam::cosim::ParcelDeposition::divideByProcessor(Placement& out) const
{
    // As the routing found them for the parcels it last sent or received: these
    if (routing_.holders().size() != out.n)
    {
        FatalErrorInFunction
            << "placing " << out.n << " parcels on a decomposed mesh, but the last routing "
            << "was of " << routing_.holders().size() << " (route them first)"
            << abort(FatalError);
    }
    out.holder = routing_.holders();
    out.mayHold = routing_.reachesThisProcessor();
    DynamicList<label> shared;
    forAll(out.holder, i)
    {
        if (out.holder[i] == -2)
        {
            shared.append(i);
        }
    }
    out.shared.transfer(shared);
}


void Foam::cosim::ParcelDeposition::agreeOnShared
(
    const labelList& shared,
    label width,
    labelList& owner
) const
{
    if (Pstream::master())
    {
        // The master has every parcel: the least over its own and what each processor found
        List<labelList> asked(Pstream::nProcs());
        for (label proc = 1; proc < Pstream::nProcs(); ++proc)
        {
            IPstream in(Pstream::commsTypes::scheduled, proc);
            labelList values;
            in >> asked[proc] >> values;
            forAll(asked[proc], k)
            {
                for (label j = 0; j < width; ++j)
                {
                    label& o = owner[asked[proc][k]*width + j];
                    o = min(o, values[k*width + j]);
                }
            }
        }
        for (label proc = 1; proc < Pstream::nProcs(); ++proc)
        {
            const labelList& which = asked[proc];
            labelList agreed(which.size()*width);
            forAll(which, k)
            {
                for (label j = 0; j < width; ++j)
                {
                    agreed[k*width + j] = owner[which[k]*width + j];
                }
            }
            OPstream out(Pstream::commsTypes::scheduled, proc);
            out << agreed;
        }
    }
    else
    {
        routing_.sendToMaster(shared, owner, width);
        IPstream in(Pstream::commsTypes::scheduled, Pstream::masterNo());
        labelList agreed;
        in >> agreed;
        forAll(shared, k)
        {
            for (label j = 0; j < width; ++j)
            {
                owner[shared[k]*width + j] = agreed[k*width + j];
            }
        }
    }
}


void Foam::cosim::ParcelDeposition::reportNotFound
(
    const labelList& centreOwner,
    Placement& out
) const
{
    const label nobody = labelMax;
    if (Pstream::master())
    {
        for (label proc = 1; proc < Pstream::nProcs(); ++proc)
        {
            IPstream in(Pstream::commsTypes::scheduled, proc);
            labelList notFound;
            in >> notFound;
            for (const label i : notFound)
            {
                out.lost[i] = true;
            }
        }
    }
    else
    {
        DynamicList<label> notFound;
        for (label i = 0; i < out.n; ++i)
        {
            if (out.holder[i] == Pstream::myProcNo() && centreOwner[i] == nobody)
            {
                notFound.append(routing_.global(i));
            }
        }
        OPstream to(Pstream::commsTypes::scheduled, Pstream::masterNo());
        to << labelList(notFound);
    }
}


void Foam::cosim::ParcelDeposition::locateCentres
(
    const std::vector<std::int64_t>& ids,
    const std::vector<double>& position,
    Placement& out
) const
{
    const label n = out.n;
    const label me = Pstream::myProcNo();
    const label nobody = labelMax;
    labelList& centreCell = out.centreCell;
    boolList& lost = out.lost;
    std::vector<std::pair<std::int64_t, label>>& seeds = out.seeds;
    auto centreOf = [&](label i)
    {
        return point(position[3*i], position[3*i + 1], position[3*i + 2]);
    };

    // 1. parcel centres, seeded by last step's cell
    centreCell.setSize(n);
    labelList centreOwner(n, nobody);
    auto cursor = lastCell_.cbegin();
    auto seedOf = [&](std::int64_t id) -> label
    {
        const auto less = [](const std::pair<std::int64_t, label>& e, std::int64_t v)
        {
            return e.first < v;
        };
        // Ascending ids: the next one is at or after the cursor
        if (cursor == lastCell_.cend() || cursor->first > id)
        {
            cursor = lastCell_.cbegin();
        }
        cursor = std::lower_bound(cursor, lastCell_.cend(), id, less);
        return (cursor != lastCell_.cend() && cursor->first == id) ? cursor->second : -1;
    };
    const bool parallel = Pstream::parRun();
    for (label i = 0; i < n; ++i)
    {
        if (parallel && !out.mayHold[i])
        {
            centreCell[i] = -1;  // outside this processor's box: in none of its cells
            continue;
        }
        centreCell[i] = locator_.locate(centreOf(i), seedOf(ids[i]));
        if (centreCell[i] >= 0)
        {
            centreOwner[i] = me;
        }
    }
    lost.setSize(n);
    if (parallel)
    {
        agreeOnShared(out.shared, 1, centreOwner);
        // A parcel one processor alone reaches is found there or nowhere; the master, which
        // answers for all, learns which of those it did not find (few: outside the mesh)
        for (label i = 0; i < n; ++i)
        {
            const label h = out.holder[i];
            lost[i] = h == -1 || ((h == -2 || h == me) && centreOwner[i] == nobody);
        }
        reportNotFound(centreOwner, out);
    }
    else
    {
        for (label i = 0; i < n; ++i)
        {
            lost[i] = (centreOwner[i] == nobody);
        }
    }
    for (label i = 0; i < n; ++i)
    {
        if (centreOwner[i] != me)
        {
            centreCell[i] = -1;
        }
        if (centreCell[i] >= 0)
        {
            seeds.emplace_back(ids[i], centreCell[i]);
        }
    }
    if (!std::is_sorted(seeds.begin(), seeds.end()))
    {
        std::sort(seeds.begin(), seeds.end());
    }
}


void Foam::cosim::ParcelDeposition::locateSatellites
(
    const std::vector<double>& position,
    const std::vector<double>& radius,
    const Placement& placed,
    label begin,
    label end,
    labelList& satCell,
    labelList& satOwner
) const
{
    const label nSat = satellites_.size();
    const label me = Pstream::myProcNo();
    const labelList& centreCell = placed.centreCell;
    const boolList& lost = placed.lost;
    auto centreOf = [&](label i)
    {
        return point(position[3*i], position[3*i + 1], position[3*i + 2]);
    };
    for (label i = begin; i < end; ++i)
    {
        if (lost[i])
        {
            continue;
        }
        const point c = centreOf(i);
        const scalar r = radius[i];
        const bool near = centreCell[i] >= 0 || locator_.inBounds(c, r);
        if (!near)
        {
            continue;
        }
        // Only the faces of the centre cell whose planes the parcel reaches can
        // put a satellite (all lie within its radius) outside that cell; none:
        // the whole parcel is inside it, and each satellite's walk would end
        // there at its first test
        constexpr label room = 64;
        label reached[room];
        const label nReached = centreCell[i] >= 0
          ? locator_.reachedFaces(c, r, centreCell[i], reached, room)
          : -1;
        if (nReached == 0)
        {
            for (label j = 0; j < nSat; ++j)
            {
                satCell[i*nSat + j] = centreCell[i];
                satOwner[i*nSat + j] = me;
            }
            continue;
        }
        for (label j = 0; j < nSat; ++j)
        {
            const point x = c + r*satellites_.offsets()[j];
            label celli = -1;
            if (nReached > 0)
            {
                // Inside the centre cell by the reached faces, else walked from
                // the cell across the face it lies beyond (a boundary face: from
                // the centre cell, whose walk ends at the boundary it leaves by)
                const label beyond = locator_.firstBeyond(x, reached, nReached);
                if (beyond < 0)
                {
                    celli = centreCell[i];
                }
                else
                {
                    const label next = locator_.across(beyond);
                    celli = locator_.walk(x, next >= 0 ? next : centreCell[i]);
                }
            }
            else if (centreCell[i] >= 0)
            {
                celli = locator_.walk(x, centreCell[i]);
            }
            if (celli < 0)
            {
                celli = locator_.search(x);
            }
            if (celli >= 0)
            {
                satCell[i*nSat + j] = celli;
                satOwner[i*nSat + j] = me;
            }
        }
    }
}


void Foam::cosim::ParcelDeposition::collectDeposits
(
    const labelList& satCell,
    const labelList& satOwner,
    Placement& out
) const
{
    const label n = out.n;
    const label nSat = satellites_.size();
    const label me = Pstream::myProcNo();
    const label nobody = labelMax;
    const labelList& centreCell = out.centreCell;
    const boolList& lost = out.lost;
    labelList& start = out.start;
    DynamicList<label>& depCell = out.depCell;
    DynamicList<scalar>& depWeight = out.depWeight;

    // 3. deposits: owned satellites, plus orphans (outside the mesh) to the centre cell;
    //    one entry per cell of a parcel (its satellites' weights added in their order), so
    //    deposit and gatherAverage visit a few cells per parcel instead of every satellite
    start.setSize(n + 1);
    depCell.clear();
    depWeight.clear();
    auto add = [&](label begin, label celli, scalar w)
    {
        for (label d = begin; d < depCell.size(); ++d)
        {
            if (depCell[d] == celli)
            {
                depWeight[d] += w;
                return;
            }
        }
        depCell.append(celli);
        depWeight.append(w);
    };
    for (label i = 0; i < n; ++i)
    {
        const label begin = depCell.size();
        start[i] = begin;
        if (lost[i])
        {
            continue;
        }
        scalar orphan = 0;
        for (label j = 0; j < nSat; ++j)
        {
            const label k = i*nSat + j;
            const scalar w = satellites_.weights()[j];
            if (satOwner[k] == me)
            {
                add(begin, satCell[k], w);
            }
            else if (satOwner[k] == nobody)
            {
                orphan += w;
            }
        }
        if (orphan > 0 && centreCell[i] >= 0)
        {
            add(begin, centreCell[i], orphan);
        }
    }
    start[n] = depCell.size();
}


void Foam::cosim::ParcelDeposition::adopt(Placement&& p)
{
    nParticles_ = p.n;
    centreCell_.transfer(p.centreCell);
    lost_.transfer(p.lost);
    start_.transfer(p.start);
    depCell_.transfer(p.depCell);
    depWeight_.transfer(p.depWeight);
    lastCell_ = std::move(p.seeds);
    if (Pstream::parRun())
    {
        DynamicList<label> held;
        for (label i = 0; i < nParticles_; ++i)
        {
            if (start_[i + 1] > start_[i] || centreCell_[i] >= 0)
            {
                held.append(i);
            }
        }
        held_.transfer(held);
    }
}


void Foam::cosim::ParcelDeposition::sumOnMaster(List<scalar>& values) const
{
    if (!Pstream::parRun())
    {
        return;
    }
    const label width = nParticles_ > 0 ? values.size()/nParticles_ : 0;
    if (Pstream::master())
    {
        // In rank order: on two processors the sums listCombineGather gave, bit for bit
        for (label proc = 1; proc < Pstream::nProcs(); ++proc)
        {
            IPstream from(Pstream::commsTypes::scheduled, proc);
            labelList which;
            List<scalar> part;
            from >> which >> part;
            forAll(which, k)
            {
                for (label j = 0; j < width; ++j)
                {
                    values[which[k]*width + j] += part[k*width + j];
                }
            }
        }
    }
    else
    {
        routing_.sendToMaster(held_, values, width);
    }
}


void Foam::cosim::ParcelDeposition::place
(
    const std::vector<std::int64_t>& ids,
    const std::vector<double>& position,
    const std::vector<double>& radius
)
{
    if (prepared_)
    {
        const std::unique_ptr<Prepared> ahead = std::move(prepared_);
        Placement p = ahead->result.get();
        if (ahead->ids == ids && ahead->position == position && ahead->radius == radius)
        {
            adopt(std::move(p));
            return;
        }
    }
    adopt(compute(ids, position, radius, threads_));
}


void Foam::cosim::ParcelDeposition::prepare
(
    const std::vector<std::int64_t>& ids,
    const std::vector<double>& position,
    const std::vector<double>& radius
)
{
    if (Pstream::parRun())
    {
        return;  // the placement talks to the other processors: main thread only
    }
    if (prepared_)
    {
        prepared_->result.wait();
    }
    prepared_.reset(new Prepared{ids, position, radius, {}});
    const Prepared& p = *prepared_;
    prepared_->result = std::async
    (
        std::launch::async,
        [this, &p]() { return compute(p.ids, p.position, p.radius, 1); }
    );
}





void Foam::cosim::ParcelDeposition::deposit
(
    const UList<scalar>& perParticle,
    scalarField& cellSum
) const
{
    for (label i = 0; i < nParticles_; ++i)
    {
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            cellSum[depCell_[d]] += depWeight_[d]*perParticle[i];
        }
    }
}


void Foam::cosim::ParcelDeposition::deposit
(
    const UList<vector>& perParticle,
    vectorField& cellSum
) const
{
    for (label i = 0; i < nParticles_; ++i)
    {
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            cellSum[depCell_[d]] += depWeight_[d]*perParticle[i];
        }
    }
}


void Foam::cosim::ParcelDeposition::gatherAverage
(
    const UList<scalar>& cellField,
    List<scalar>& perParticle
) const
{
    perParticle.setSize(nParticles_);
    for (label i = 0; i < nParticles_; ++i)
    {
        scalar sum = 0;
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            sum += depWeight_[d]*cellField[depCell_[d]];
        }
        perParticle[i] = sum;
    }
}


void Foam::cosim::ParcelDeposition::gatherAverage
(
    const UList<vector>& cellField,
    List<vector>& perParticle
) const
{
    perParticle.setSize(nParticles_);
    for (label i = 0; i < nParticles_; ++i)
    {
        vector sum(Zero);
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            sum += depWeight_[d]*cellField[depCell_[d]];
        }
        perParticle[i] = sum;
    }
}
