#include "ParcelDeposition.H"
#include "Pstream.H"
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
    )
{}


void Foam::cosim::ParcelDeposition::place
(
    const std::vector<std::int64_t>& ids,
    const std::vector<double>& position,
    const std::vector<double>& radius
)
{
    const label n = label(ids.size());
    const label nSat = satellites_.size();
    const label me = Pstream::myProcNo();
    const label nobody = labelMax;
    nParticles_ = n;

    auto centreOf = [&](label i)
    {
        return point(position[3*i], position[3*i + 1], position[3*i + 2]);
    };

    // 1. parcel centres, seeded by last step's cell
    centreCell_.setSize(n);
    labelList centreOwner(n, nobody);
    for (label i = 0; i < n; ++i)
    {
        const auto seed = lastCell_.find(ids[i]);
        centreCell_[i] =
            locator_.locate(centreOf(i), seed == lastCell_.end() ? -1 : seed->second);
        if (centreCell_[i] >= 0)
        {
            centreOwner[i] = me;
        }
    }
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(centreOwner, minEqOp<label>());
        Pstream::listCombineScatter(centreOwner);
    }
    lost_.setSize(n);
    lastCell_.clear();
    for (label i = 0; i < n; ++i)
    {
        if (centreOwner[i] != me)
        {
            centreCell_[i] = -1;
        }
        lost_[i] = (centreOwner[i] == nobody);
        if (centreCell_[i] >= 0)
        {
            lastCell_[ids[i]] = centreCell_[i];
        }
    }

    // 2. satellite points, seeded by the centre cell. Independent per parcel, so on one
    //    processor they are split over threads: the DEM waits for these samples, its core is
    //    free. Each point is located exactly as by one thread (same cells, same order of work
    //    within a parcel).
    labelList satCell(n*nSat, label(-1));
    labelList satOwner(n*nSat, nobody);
    auto satellitesOf = [&](label begin, label end)
    {
        for (label i = begin; i < end; ++i)
        {
            if (lost_[i])
            {
                continue;
            }
            const point c = centreOf(i);
            const scalar r = radius[i];
            const bool near = centreCell_[i] >= 0 || locator_.inBounds(c, r);
            if (!near)
            {
                continue;
            }
            for (label j = 0; j < nSat; ++j)
            {
                const point x = c + r*satellites_.offsets()[j];
                label celli = -1;
                if (centreCell_[i] >= 0)
                {
                    celli = locator_.walk(x, centreCell_[i]);
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
    };
    const label nThreads = (Pstream::parRun() || n < 512) ? 1 : threads_;
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
        Pstream::listCombineGather(satOwner, minEqOp<label>());
        Pstream::listCombineScatter(satOwner);
    }

    // 3. deposits: owned satellites, plus orphans (outside the mesh) to the centre cell
    start_.setSize(n + 1);
    depCell_.clear();
    depWeight_.clear();
    for (label i = 0; i < n; ++i)
    {
        start_[i] = depCell_.size();
        if (lost_[i])
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
                depCell_.append(satCell[k]);
                depWeight_.append(w);
            }
            else if (satOwner[k] == nobody)
            {
                orphan += w;
            }
        }
        if (orphan > 0 && centreCell_[i] >= 0)
        {
            depCell_.append(centreCell_[i]);
            depWeight_.append(orphan);
        }
    }
    start_[n] = depCell_.size();
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
